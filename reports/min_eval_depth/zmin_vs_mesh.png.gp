set terminal pngcairo size 900,600 font 'sans,11'
set output 'zmin_vs_mesh.png'
set datafile separator ','
set xlabel 'mesh size dx (um)'
set ylabel 'minimum evaluation depth z_{min} (um)'
set grid
set key top left
set xrange [0:2.1]
set yrange [0:*]
plot 'zmin.csv' using 1:4 with points pt 7 ps 1.2 lc 1 title 'node, 1 %', -1.98565e-06 + 1.315*x with lines lc 1 notitle, '' using 1:5 with points pt 5 ps 1.2 lc 2 title 'node, 0.5 %', -2.30099e-06 + 1.43601*x with lines lc 2 notitle, '' using 1:6 with points pt 9 ps 1.2 lc 3 title 'node, 0.2 %', -2.52563e-06 + 1.59529*x with lines lc 3 notitle, '' using 1:7 with points pt 11 ps 1.2 lc 4 title 'node, 0.1 %', -2.2213e-06 + 1.71524*x with lines lc 4 notitle, '' using 1:14 with points pt 6 ps 1.2 lc 7 title 'edge midpoint, 0.2 %', 1.625*x with lines dt 2 lc rgb 'red' title 'paper ratio 1.3/0.8', '-' using 1:2 with points pt 3 ps 2.5 lw 2 lc rgb 'red' title 'paper: 0.8 um -> 1.3 um'
0.8,1.3
e
