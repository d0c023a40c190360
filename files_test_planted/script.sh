ln -s victim res.txt.tmp.$$ && exec $DEWALL triangulate p.txt -o res.txt
