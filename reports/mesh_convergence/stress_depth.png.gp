set terminal pngcairo size 900,600 font 'sans,11'
set output 'stress_depth.png'
set datafile separator ','
set xlabel 'depth z, um (paper: x)'
set ylabel 'von Mises stress, MPa'
set grid
set key top right
set xrange [0:6]
plot for [i=0:4] 'stress_depth.csv' index i using 2:3 with lines lw 2 title sprintf('dx = %s um', word('2.0 1.6 1.2 0.8 0.4', i+1)), 700 with lines dt 2 lc rgb 'black' title 'Y'
