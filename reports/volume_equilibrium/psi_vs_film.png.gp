set terminal pngcairo size 900,600 font 'sans,11'
set output 'psi_vs_film.png'
set datafile separator ','
set xlabel 'h_{EHD} [um]'
set ylabel 'psi'
set grid
plot 'roots.csv' every ::1 using 1:8 with linespoints pt 7 title 'psi_{load}', '' every ::1 using 1:9 with linespoints pt 5 title 'psi_{area}'
