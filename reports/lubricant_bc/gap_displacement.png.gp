set terminal pngcairo size 900,600 font 'sans,11'
set output 'gap_displacement.png'
set datafile separator ','
set multiplot layout 2,1
set grid
set xrange [-0.5:0.5]
set format x ''
set key bottom center maxrows 2
set ylabel 'surface - counter face (um)'
set yrange [:0.05]
set lmargin 12
set tmargin 1
set bmargin 0.5
plot 0 with lines lw 3 lc rgb 'black' title 'counter face', 'profiles.csv' using 2:(-$11) with lines lw 2 lc rgb '#1f77b4' title 'loaded surface, dry', '' using 2:(-$12) with lines lw 2 dt 2 lc rgb '#d62728' title 'loaded surface, lubricated', '' using 2:($3 - 0.5) with lines lw 1 lc rgb 'gray' title 'unloaded (touching)'
set format x '%g'
set xlabel 'x / wavelength (rolling direction)'
set ylabel 'u - u(crest) (um)'
set autoscale y
set key bottom center
set tmargin 0.5
set bmargin 3
plot 'profiles.csv' using 2:9 with lines lw 2 lc rgb '#1f77b4' title 'dry', '' using 2:10 with lines lw 2 dt 2 lc rgb '#d62728' title 'lubricated'
unset multiplot
