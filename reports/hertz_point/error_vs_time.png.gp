set terminal pngcairo size 900,600 font 'sans,11'
set output 'error_vs_time.png'
set datafile separator ','
set logscale xy
set key top right
set xlabel 'run time (s)'
set ylabel 'relative error'
set grid
plot 'convergence.csv' using 4:7 with linespoints pt 7 title 'p_{max}', '' using 4:9 with linespoints pt 5 title 'approach', '' using 4:11 with linespoints pt 9 title 'radius (fit)'
