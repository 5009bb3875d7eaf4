set terminal pngcairo size 900,600 font 'sans,11'
set output 'hertz_work_precision.png'
set datafile separator ','
set logscale xy
set key top right
set xlabel 'run time (s)'
set ylabel 'relative error of p_{max}'
set grid
plot 'hertz.csv' using (strcol(1) eq 'cg_fft' ? $5 : 1/0):9 with linespoints pt 7 title 'cg, fft', '' using (strcol(1) eq 'pk_fft' ? $5 : 1/0):9 with linespoints pt 5 title 'pk, fft', '' using (strcol(1) eq 'cg_direct' ? $5 : 1/0):9 with points pt 9 ps 1.5 title 'cg, direct', '' using (strcol(1) eq 'pk_direct' ? $5 : 1/0):9 with points pt 11 ps 1.5 title 'pk, direct'
