$DEWALL triangulate p.txt -o /proc/self/fd/1 | cat > piped.txt
