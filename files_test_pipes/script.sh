cat q.txt | $DEWALL draw /dev/stdin s.txt
