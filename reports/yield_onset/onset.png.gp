set terminal pngcairo size 900,600 font 'sans,11'
set output 'onset.png'
set datafile separator ','
set grid
set key top left
set logscale y
set xlabel 'p0 / onset p0'
set ylabel 'max equivalent plastic strain (1e-12 = none)'
set xrange [0.98:1.02]
plot 'onset.csv' every ::1::2 using 2:($7 + 1e-12) with linespoints pt 7 title 'Hertz sphere', '' every ::3::4 using 2:($7 + 1e-12) with linespoints pt 5 title 'Hertz cylinder (plane strain)'
