set terminal pngcairo size 900,600 font 'sans,11'
set output 'profile.png'
set datafile separator ','
set key top right
set xlabel 'x / a'
set ylabel 'p / p_0'
set grid
set samples 1000
plot 'profile.csv' using 1:3 with lines lw 2 title 'Hertz', 'profile.csv' using 1:2 with points pt 7 ps 0.6 title 'microcontact'
