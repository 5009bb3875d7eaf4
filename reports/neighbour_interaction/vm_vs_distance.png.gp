set terminal pngcairo size 900,600 font 'sans,11'
set output 'vm_vs_distance.png'
pats = 'line3 cross5 square3x3 square5x5 square7x7'
labs = 'line_of_3 cross_of_5 3x3 5x5 7x7'
set datafile separator ','
set xlabel 'centre distance d / a'
set ylabel '{/Symbol s}_{vM,max} / {/Symbol s}_{vM,max,isolated}'
set grid
set key bottom right noenhanced
set yrange [0.65:1.01]
plot for [i=1:5] 'ratios.csv' using (strcol(1) eq word(pats,i) ? $4 : 1/0):6 with points pt 7 ps 1.3 lc i title word(labs,i), for [i=1:5] 'ratios.csv' using (strcol(1) eq word(pats,i) ? $4 : 1/0):10 with lines lc i notitle, 'infinite.csv' using 1:2 with points pt 5 ps 1.3 lc rgb 'black' title 'infinite array', '' using 1:5 with lines dt 2 lc rgb 'black' notitle, 0.84 with lines dt 3 lw 2 lc rgb 'red' title 'paper: -16 %'
