set terminal pngcairo size 900,600 font 'sans,11'
set output 'hertz_iterations.png'
set datafile separator ','
set logscale x 2
set key top left
set xlabel 'N (N x N grid)'
set ylabel 'iterations'
set grid
plot 'hertz.csv' using (strcol(1) eq 'cg_fft' ? $2 : 1/0):3 with linespoints pt 7 title 'cg (preconditioned, nested start)', '' using (strcol(1) eq 'pk_fft' ? $2 : 1/0):3 with linespoints pt 5 title 'pk'
