# head_on_inelastic: error against cost: rerun with `gnuplot error_cost_head_on_inelastic.gp` in this directory.
set terminal svg size 900,500 dynamic enhanced font 'Helvetica,13' background '#ffffff'
set output 'error_cost_head_on_inelastic.svg'
set title 'head_on_inelastic: error against cost' noenhanced
set xlabel 'µs per simulated second' noenhanced
set ylabel 'error (m)' noenhanced
set grid lc rgb '#dddddd'
set key outside below center horizontal maxcols 4 noenhanced
set datafile missing 'NaN'
set logscale x
set format x '10^{%L}'
set logscale y
set format y '10^{%L}'
plot 'error_cost_head_on_inelastic.dat' index 0 using 1:2 with linespoints lw 1.5 dt 1 pt 7 ps 0.7 lc rgb '#0072B2' title 'own', \
     'error_cost_head_on_inelastic.dat' index 1 using 1:2 with lines lw 1.2 dt 2 lc rgb '#0072B2' title 'own iterations x4', \
     'error_cost_head_on_inelastic.dat' index 2 using 1:2 with linespoints lw 1.5 dt 1 pt 7 ps 0.7 lc rgb '#D55E00' title 'ode', \
     'error_cost_head_on_inelastic.dat' index 3 using 1:2 with lines lw 1.2 dt 2 lc rgb '#D55E00' title 'ode iterations x4', \
     'error_cost_head_on_inelastic.dat' index 4 using 1:2 with linespoints lw 1.5 dt 1 pt 7 ps 0.7 lc rgb '#009E73' title 'bullet', \
     'error_cost_head_on_inelastic.dat' index 5 using 1:2 with lines lw 1.2 dt 2 lc rgb '#009E73' title 'bullet iterations x4', \
     'error_cost_head_on_inelastic.dat' index 6 using 1:2 with linespoints lw 1.5 dt 1 pt 7 ps 0.7 lc rgb '#E69F00' title 'mujoco', \
     'error_cost_head_on_inelastic.dat' index 7 using 1:2 with lines lw 1.2 dt 2 lc rgb '#E69F00' title 'mujoco iterations x4', \
     'error_cost_head_on_inelastic.dat' index 8 using 1:2 with linespoints lw 1.5 dt 1 pt 7 ps 0.7 lc rgb '#8C564B' title 'dart', \
     'error_cost_head_on_inelastic.dat' index 9 using 1:2 with lines lw 1.2 dt 2 lc rgb '#8C564B' title 'dart iterations x4', \
     'error_cost_head_on_inelastic.dat' index 10 using 1:2 with linespoints lw 1.5 dt 1 pt 7 ps 0.7 lc rgb '#882255' title 'jolt', \
     'error_cost_head_on_inelastic.dat' index 11 using 1:2 with lines lw 1.2 dt 2 lc rgb '#882255' title 'jolt iterations x4', \
     'error_cost_head_on_inelastic.dat' index 12 using 1:2 with linespoints lw 1.5 dt 1 pt 7 ps 0.7 lc rgb '#44AA99' title 'rapier', \
     'error_cost_head_on_inelastic.dat' index 13 using 1:2 with lines lw 1.2 dt 2 lc rgb '#44AA99' title 'rapier iterations x4'
