set terminal pngcairo size 900,600 font 'sans,11'
set output 'loads.png'
set datafile separator ','
set logscale x
set key top left
set format x '10^{%L}'
set xlabel 'load (N)'
set ylabel 'iterations'
set y2label 'contact ratio'
set y2tics
set grid
set datafile missing 'nan'
plot 'loads.csv' using 1:3 with linespoints pt 7 title 'fft cg', '' using 1:4 with linespoints pt 5 title 'fft pk', '' using 1:5 with linespoints pt 9 dt 2 title 'direct cg', '' using 1:6 with linespoints pt 11 dt 2 title 'direct pk', '' using 1:2 axes x1y2 with lines lw 2 lc 'gray' title 'contact ratio'
