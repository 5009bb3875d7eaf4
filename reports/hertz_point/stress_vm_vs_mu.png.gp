set terminal pngcairo size 900,600 font 'sans,11'
set output 'stress_vm_vs_mu.png'
set datafile separator ','
set xlabel 'friction coefficient {/Symbol m}'
set ylabel 'max {/Symbol s}_{vM} / p_0'
set grid
set key top left noenhanced
plot 'stress_vm_vs_mu.csv' using 1:5 with points lw 2 pt 6 ps 2 title 'reference (hertz_point_vm_vs_mu.csv; point mu >= 0.4: corrected edge values)', '' using 1:2 with points pt 7 ps 1.2 title 'microcontact (a/dx = 40)'
