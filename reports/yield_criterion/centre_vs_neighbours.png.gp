set terminal pngcairo size 900,600 font 'sans,11'
set output 'centre_vs_neighbours.png'
set datafile separator ','
set xlabel 'neighbouring asperities'
set ylabel 'centre asperity / single asperity'
set grid
set key top left opaque box noenhanced
set xrange [-1:25]
set xtics (0, 2, 4, 8, 24)
set yrange [0.3:1.9]
plot 'centre_ratios.csv' every ::1 using 2:9 with linespoints pt 5 ps 1.5 lw 2 title 'pressure cap: dent', '' every ::1 using 2:5 with linespoints pt 7 ps 1.5 lw 2 title 'von Mises: dent', '' every ::1 using 2:7 with linespoints pt 9 ps 1.3 title 'von Mises: max plastic strain', '' every ::1 using 2:3 with linespoints dt 2 pt 6 title 'elastic vM peak', '' every ::1 using 2:4 with lines dt 3 lc rgb 'black' title 'elastic vM, Hamilton', '' every ::1 using 2:13 with linespoints dt 4 pt 4 lc rgb 'gray50' title 'plain spheres: cap dent'
