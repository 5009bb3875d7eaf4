set terminal pngcairo size 900,600 font 'sans,11'
set output 'whole_mu.png'
set datafile separator ','
set grid
set key outside right
set xlabel 'disc speed [rpm]'
set ylabel 'mu'
set logscale x
plot 'runin.csv' every ::1 using ($1 == 109 && strcol(2) eq 'down' ? $3 : 1/0):9 with linespoints pt 7 lc 1 title '109 N run-down', 'runin.csv' every ::1 using ($1 == 109 && strcol(2) eq 'up' ? $3 : 1/0):9 with linespoints pt 6 lc 1 title '109 N run-up', 'runin.csv' every ::1 using ($1 == 218 && strcol(2) eq 'down' ? $3 : 1/0):9 with linespoints pt 7 lc 2 title '218 N run-down', 'runin.csv' every ::1 using ($1 == 218 && strcol(2) eq 'up' ? $3 : 1/0):9 with linespoints pt 6 lc 2 title '218 N run-up', 'runin.csv' every ::1 using ($1 == 327 && strcol(2) eq 'down' ? $3 : 1/0):9 with linespoints pt 7 lc 3 title '327 N run-down', 'runin.csv' every ::1 using ($1 == 327 && strcol(2) eq 'up' ? $3 : 1/0):9 with linespoints pt 6 lc 3 title '327 N run-up'
