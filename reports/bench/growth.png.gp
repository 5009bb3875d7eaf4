set terminal pngcairo size 900,600 font 'sans,11'
set output 'growth.png'
set datafile separator ','
set logscale xy
set key top left
set xlabel 'surface cells N'
set ylabel 'time (s)'
set grid
f(x) = 1e-7*x
g(x) = 1e-9*x*x
plot for [c in 'elastic stress_layer eigen_disp eigen_stress ep_sphere runin_step direct fft_pair'] 'growth.csv' using 3:(strcol(1) eq c ? $4 : NaN) with linespoints title c, [64:2e6] f(x) with lines dt 2 lc rgb 'gray' title '~N', [64:1e5] g(x) with lines dt 3 lc rgb 'gray' title '~N²'
