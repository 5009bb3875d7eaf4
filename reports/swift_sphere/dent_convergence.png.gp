set terminal pngcairo size 900,600 font 'sans,11'
set output 'dent_convergence.png'
set datafile separator ','
set grid
set key bottom right
set xlabel 'dx / a'
set ylabel 'residual dent [um]'
plot 'swift.csv' every ::1 using 3:8 with linespoints pt 7 title 'microcontact', '' every ::1 using 3:($12 > 0 ? $12 : 1/0) with points pt 6 ps 2 title 'dossier reference loop'
