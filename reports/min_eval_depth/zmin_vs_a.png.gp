set terminal pngcairo size 900,600 font 'sans,11'
set output 'zmin_vs_a.png'
set datafile separator ','
set xlabel 'a / dx'
set ylabel 'z_{min} / dx'
set grid
set key outside right
set yrange [0.8:1.9]
plot 'zmin.csv' using 3:($4/$1) with points pt 7 title 'node 1 %', '' using 3:($6/$1) with points pt 9 title 'node 0.2 %', '' using 3:($10/$1) with points pt 5 title 'corner 0.2 %', '' using 3:($15/$1) with points pt 11 title 'edge 0.1 %', 1.3200 dt 2 lc 1 title 'table', 1.6000 dt 2 lc 2 notitle, 1.6000 dt 2 lc 3 notitle, 1.2200 dt 2 lc 4 notitle
