set terminal pngcairo size 900,600 font 'sans,11'
set output 'whole_psi.png'
set datafile separator ','
set grid
set key outside right
set xlabel 'h_{pocket} [um]'
set ylabel 'psi_{load}'
plot 'runin.csv' every ::1 using ($1 == 1086 && strcol(2) eq 'down' ? $8 : 1/0):6 with linespoints pt 7 lc 1 title '1086 N run-down', 'runin.csv' every ::1 using ($1 == 1086 && strcol(2) eq 'up' ? $8 : 1/0):6 with linespoints pt 6 lc 1 title '1086 N run-up', 'runin.csv' every ::1 using ($1 == 2172 && strcol(2) eq 'down' ? $8 : 1/0):6 with linespoints pt 7 lc 2 title '2172 N run-down', 'runin.csv' every ::1 using ($1 == 2172 && strcol(2) eq 'up' ? $8 : 1/0):6 with linespoints pt 6 lc 2 title '2172 N run-up', 'runin.csv' every ::1 using ($1 == 3258 && strcol(2) eq 'down' ? $8 : 1/0):6 with linespoints pt 7 lc 3 title '3258 N run-down', 'runin.csv' every ::1 using ($1 == 3258 && strcol(2) eq 'up' ? $8 : 1/0):6 with linespoints pt 6 lc 3 title '3258 N run-up'
