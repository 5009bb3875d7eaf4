set terminal pngcairo size 900,600 font 'sans,11'
set output 'stress_axis.png'
set datafile separator ','
set xlabel 'z / b'
set ylabel 'stress / p_0'
set grid
set key bottom right
set xrange [0:3]
plot 'stress_axis.csv' using 1:7 with lines lw 2 lc 1 title '{/Symbol s}_{xx} exact', '' using 1:2 with points pt 7 ps 0.6 lc 1 title '{/Symbol s}_{xx}', '' using 1:8 with lines lw 2 dt 2 lc 2 title '{/Symbol s}_{yy} exact', '' using 1:3 with points pt 6 ps 0.9 lc 2 title '{/Symbol s}_{yy}', '' using 1:9 with lines lw 2 lc 3 title '{/Symbol s}_{zz} exact', '' using 1:4 with points pt 5 ps 0.6 lc 3 title '{/Symbol s}_{zz}', '' using 1:10 with lines lw 2 lc 4 title 'von Mises exact', '' using 1:5 with points pt 9 ps 0.7 lc 4 title 'von Mises', '' using 1:11 with lines lw 2 lc 7 title 'Tresca exact', '' using 1:6 with points pt 11 ps 0.7 lc 7 title 'Tresca'
