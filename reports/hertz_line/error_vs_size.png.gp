set terminal pngcairo size 900,600 font 'sans,11'
set output 'error_vs_size.png'
set datafile separator ','
set logscale xy
set key bottom right
set xlabel 'dx / b'
set ylabel 'error'
set grid
plot 'convergence.csv' using 3:7 with linespoints pt 7 title 'p_{max}', '' using 3:9 with linespoints pt 5 title 'half-width (fit)', '' using 3:10 with linespoints pt 9 title 'profile (|x| < 0.9b)', '' using 3:(0.15*$3**2) with lines dt 2 title 'tolerance p_{max}: 0.15 (dx/b)^2'
