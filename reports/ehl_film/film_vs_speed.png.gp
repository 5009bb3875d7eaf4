set terminal pngcairo size 900,600 font 'sans,11'
set output 'film_vs_speed.png'
set datafile separator ','
set logscale xy
set xlabel 'disc speed [rpm]'
set ylabel 'h [um]'
set grid
set key top left
plot 'film_vs_speed.csv' using 1:2 with lines lw 2 title 'Pan-Hamrock central', '' using 1:3 with lines title 'Pan-Hamrock min', '' using 1:4 with lines title 'Dowson-Toyoda', '' using 1:5 with lines title 'Dowson-Higginson', 'disc_case.csv' using ($1 == 0.03 && strcol(3) eq 'pan_hamrock_central' ? $2 : 1/0):4 with points pt 7 title 'table: Pan-Hamrock central', 'disc_case.csv' using ($1 == 0.03 && strcol(3) eq 'dowson_higginson' ? $2 : 1/0):4 with points pt 5 title 'table: Dowson-Higginson'
