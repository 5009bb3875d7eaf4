set terminal pngcairo size 900,600 font 'sans,11'
set output 'plastic_vs_mesh.png'
set datafile separator ','
set xlabel 'mesh size dx = dy, um'
set ylabel 'relative to the finest mesh'
set grid
set key below
set xrange [0:2.2]
plot 'measures.csv' using 1:($5/5.01258) with linespoints pt 7 lw 2 title 'largest residual displacement', '' using 1:($6/0.096116) with linespoints pt 5 lw 2 title 'dent volume', '' using 1:($8/0.161331) with linespoints pt 9 title 'int p dV', '' using 1:($7/0.00374946) with linespoints pt 11 title 'largest plastic strain', '' using 1:($9/124.192) with linespoints pt 13 title 'plastic volume', '' using 1:($3/1218.25) with linespoints dt 2 pt 6 title 'elastic von Mises max', 1 with lines dt 3 lc rgb 'black' notitle
