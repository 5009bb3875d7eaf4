set terminal pngcairo size 900,600 font 'sans,11'
set output 'operator.png'
set datafile separator ','
set logscale xy
set key top left
set xlabel 'N'
set ylabel 'time (s)'
set grid
plot 'operator.csv' using 1:4 with linespoints pt 7 title 'mc\_operator\_apply (fft)', '' using 1:5 with linespoints pt 5 title 'FFTW r2c + c2r pair'
