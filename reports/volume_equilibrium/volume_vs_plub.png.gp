set terminal pngcairo size 900,600 font 'sans,11'
set output 'volume_vs_plub.png'
set datafile separator ','
set xlabel 'p_{lub} / p_{nom}'
set ylabel 'V / A_{nom} [um]'
set grid
plot 'volume_vs_plub.csv' every ::1 using 1:2 with linespoints pt 7 title 'V(p_{lub})', 'roots.csv' every ::1 using ($3 / 1000):1 with points pt 5 ps 1.5 title 'roots: h_{EHD}'
