set terminal pngcairo size 900,600 font 'sans,11'
set output 'profile.png'
set datafile separator ','
set xlabel 'x / b'
set ylabel 'p / p_0'
set grid
plot 'profile.csv' using 1:3 with lines lw 2 title 'Hertz', '' using 1:2 with points pt 7 ps 0.5 title 'microcontact'
