set terminal pngcairo size 900,600 font 'sans,11'
set output 'min_depth.png'
set datafile separator ','
set xlabel 'mesh size dx, um'
set ylabel 'depth, um'
set grid
set key top left
set xrange [0:2.2]
plot 'measures.csv' using 1:($1*$12) with linespoints pt 7 lw 2 title 'point kernel z_{min}, 1 %', '' using 1:($1*$13) with linespoints pt 5 lw 2 title 'point kernel z_{min}, 0.2 %', x*1.307 with lines dt 2 title '1.307 dx', x*1.591 with lines dt 2 title '1.591 dx', 0.996919 with lines dt 3 lc rgb 'black' title 'depth of the von Mises maximum', '-' with points pt 3 ps 2 lc rgb 'red' title 'paper: 1.3 um at 0.8 um'
0.8,1.3
e
