set terminal pngcairo size 900,600 font 'sans,11'
set output 'ke_work_precision.png'
set datafile separator ','
set logscale x
set key top right
set xlabel 'run time (s)'
set ylabel 'error against the KE fit (%)'
set grid
plot 'ke_work_precision.csv' using 8:(100*$5) with linespoints pt 7 title 'w/w_c', '' using 8:(100*$7) with linespoints pt 5 title 'A/A_c'
