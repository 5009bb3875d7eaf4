set terminal pngcairo size 900,600 font 'sans,11'
set output 'szz_vs_depth.png'
set datafile separator ','
set xlabel 'z / dx'
set ylabel '{/Symbol s}_{zz} / p_0'
set grid
set key bottom right
set yrange [-2:0.05]
set xrange [0:2.5]
plot 'profile.csv' using 1:4 with lines lw 3 lc rgb 'black' title 'Hamilton (node)', '' using 1:2 with lines lw 2 title 'point kernel, node', '' using 1:7 with lines lw 2 title 'point kernel, corner', '' using 1:12 with lines lw 2 title 'point kernel, edge', '' using 1:3 with points pt 7 ps 0.5 title 'patch kernel, node', '' using 1:8 with points pt 5 ps 0.5 title 'patch kernel, corner', '' using 1:13 with points pt 9 ps 0.5 title 'patch kernel, edge'
