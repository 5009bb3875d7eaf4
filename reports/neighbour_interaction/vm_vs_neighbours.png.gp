set terminal pngcairo size 900,600 font 'sans,11'
set output 'vm_vs_neighbours.png'
set datafile separator ','
set xlabel 'number of neighbouring cells'
set ylabel '{/Symbol s}_{vM,max} / {/Symbol s}_{vM,max,isolated}'
set grid
set logscale x
set xtics (2, 4, 8, 24, 48)
set key bottom left
set xrange [1.7:60]
plot 'by_neighbours.csv' using 1:2 with linespoints pt 7 title 'd = 2a', '' using 1:3 with linespoints pt 5 title 'd = 2.5a', '' using 1:4 with linespoints pt 9 title 'd = 3a', '' using 1:5 with linespoints pt 11 title 'd = 4a', '' using 1:6 with linespoints pt 13 title 'd = 5a', '' using 1:8 with linespoints pt 3 title 'd = 8a', 0.84 with lines dt 3 lc rgb 'red' title 'paper: -16 %'
