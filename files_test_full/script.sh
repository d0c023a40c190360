$DEWALL draw p.txt s.txt > full
