set terminal pngcairo size 900,600 font 'sans,11'
set output 'error_vs_size.png'
set datafile separator ','
set logscale xy
set key bottom right
set xlabel 'dx / a'
set ylabel 'relative error'
set grid
plot 'convergence.csv' using 3:7 with linespoints pt 7 title 'p_{max}', '' using 3:9 with linespoints pt 5 title 'approach', '' using 3:11 with linespoints pt 9 title 'radius (fit)', '' using 3:(0.15*$3**2) with lines dt 2 title 'tolerance p_{max}, approach: 0.15 (dx/a)^2'
