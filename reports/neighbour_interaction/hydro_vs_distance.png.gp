set terminal pngcairo size 900,600 font 'sans,11'
set output 'hydro_vs_distance.png'
pats = 'line3 cross5 square3x3 square5x5 square7x7'
labs = 'line_of_3 cross_of_5 3x3 5x5 7x7'
set datafile separator ','
set xlabel 'centre distance d / a'
set ylabel '{/Symbol s}_{h} / {/Symbol s}_{h,isolated}'
set grid
set key top right noenhanced
plot for [i=1:5] 'ratios.csv' using (strcol(1) eq word(pats,i) ? $4 : 1/0):9 with points pt 7 ps 1.3 lc i title word(labs,i), for [i=1:5] 'ratios.csv' using (strcol(1) eq word(pats,i) ? $4 : 1/0):11 with lines lc i notitle, 'infinite.csv' using 1:3 with linespoints dt 2 pt 5 lc rgb 'black' title 'infinite array'
