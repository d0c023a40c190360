umask 022 && $DEWALL generate uniform 10 --dim 2 -o new.txt
