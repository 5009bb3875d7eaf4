set terminal pngcairo size 900,600 font 'sans,11'
set output 'error_vs_depth.png'
set datafile separator ','
set logscale y
set format y '10^{%L}'
set xlabel 'z / dx'
set ylabel 'relative error of {/Symbol s}_{zz}'
set grid
set key top right
set xrange [0:2.5]
set yrange [1e-9:10]
plot 'profile.csv' using 1:5 with lines lw 2 title 'point, node', '' using 1:10 with lines lw 2 title 'point, corner', '' using 1:15 with lines lw 2 title 'point, edge', '' using 1:17 with lines dt 2 lc rgb 'gray30' title 'Poisson sum, node', '' using 1:19 with lines dt 3 lc rgb 'gray30' title 'Poisson sum, edge', '' using 1:($6+1e-12) with points pt 7 ps 0.4 title 'patch, node', '' using 1:($11+1e-12) with points pt 5 ps 0.4 title 'patch, corner', '' using 1:($16+1e-12) with points pt 9 ps 0.4 title 'patch, edge', 0.0016 with lines dt 4 lc rgb 'red' title 'eps = 0.16 %'
