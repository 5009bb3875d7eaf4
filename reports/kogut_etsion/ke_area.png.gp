set terminal pngcairo size 900,600 font 'sans,11'
set output 'ke_area.png'
set datafile separator ','
set grid
set key top left
set xlabel 'P / P_c'
set ylabel 'A / A_c'
plot 'ke.csv' every ::1 using 1:3 with points pt 7 title 'microcontact', '' every ::1 using 1:4 with points pt 6 title 'cell count', '' every ::1 using 1:6 with linespoints lw 2 title 'Kogut-Etsion fit', '' every ::1 using 1:7 with linespoints dt 2 title 'Hertz'
