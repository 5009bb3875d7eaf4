set terminal pngcairo size 900,600 font 'sans,11'
set output 'pressure_profile.png'
set datafile separator ','
set xlabel 'x / wavelength (rolling direction)'
set ylabel 'pressure p (MPa)'
set grid
set key top right
set xrange [-0.5:0.5]
plot 'profiles.csv' using 2:7 with lines lw 2 lc rgb '#1f77b4' title 'dry: Westergaard', '' using 2:4 with points pt 7 ps 0.5 lc rgb '#1f77b4' title 'dry: microcontact', '' using 2:8 with lines lw 2 lc rgb '#d62728' title 'lubricated: p_{lub} + Westergaard(p_{mean} - p_{lub})', '' using 2:5 with points pt 5 ps 0.5 lc rgb '#d62728' title 'lubricated: microcontact', '' using 2:6 with lines dt 2 lw 2 lc rgb 'black' title 'lubricant floor p_{lub}'
