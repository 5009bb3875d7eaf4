set terminal pngcairo size 900,600 font 'sans,11'
set output 'profiles.png'
set datafile separator ','
set xlabel 'x / a'
set ylabel 'permanent deformation u_r, nm'
set grid
set key top right noenhanced
pats = 'single line3 cross5 square3x3 square5x5'
plot for [i=1:5] 'profiles.csv' using (strcol(1) eq word(pats,i) ? $2 : 1/0):3 with lines lw 2 lc i title 'von Mises, '.word(pats,i), for [i=1:5] 'profiles.csv' using (strcol(1) eq word(pats,i) ? $2 : 1/0):4 with lines dt 2 lc i title 'cap, '.word(pats,i)
