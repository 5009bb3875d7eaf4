set terminal pngcairo size 900,600 font 'sans,11'
set output 'pockets_vs_plub.png'
set datafile separator ','
set xlabel 'p_{lub} / p_{mean}'
set ylabel 'mean gap (um)'
set y2label 'solid load fraction {/Symbol y}_F'
set ytics nomirror
set y2tics
set grid
set key top left
plot 'sweep.csv' using 1:2 with linespoints pt 7 title 'mean gap', '' using 1:3 axes x1y2 with linespoints pt 5 title '{/Symbol y}_F (right)'
