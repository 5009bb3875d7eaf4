set terminal pngcairo size 900,600 font 'sans,11'
set output 'profiles.png'
set datafile separator ','
set xlabel 'x, um'
set ylabel 'residual displacement u_r (into the body), nm'
set grid
set key top left
plot for [i=0:4] 'profiles.csv' index i using 2:3 with linespoints pt 7 ps 0.5 title sprintf('dx = %s um', word('2.0 1.6 1.2 0.8 0.4', i+1))
