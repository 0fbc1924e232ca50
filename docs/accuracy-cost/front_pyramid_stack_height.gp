# ../../fixtures/scenes/pyramid.json: stack_height against cost: rerun with `gnuplot front_pyramid_stack_height.gp` in this directory.
set terminal svg size 900,480 dynamic enhanced font 'Helvetica,13' background '#ffffff'
set output 'front_pyramid_stack_height.svg'
set title '../../fixtures/scenes/pyramid.json: stack_height against cost' noenhanced
set xlabel 'µs per simulated second' noenhanced
set ylabel 'stack_height (m)' noenhanced
set grid lc rgb '#dddddd'
set key outside right top noenhanced
set datafile missing 'NaN'
set logscale x
set format x '10^{%L}'
set logscale y
set format y '10^{%L}'
plot 'front_pyramid_stack_height.dat' index 0 using 1:2 with points pt 7 ps 0.5 lc rgb '#0072B2' title 'bullet', \
     'front_pyramid_stack_height.dat' index 1 using 1:2 with lines lw 1.2 dt 2 lc rgb '#0072B2' title 'bullet front', \
     'front_pyramid_stack_height.dat' index 2 using 1:2 with points pt 7 ps 0.5 lc rgb '#D55E00' title 'ode', \
     'front_pyramid_stack_height.dat' index 3 using 1:2 with points pt 2 ps 0.9 lc rgb '#D55E00' title 'ode (fails a check)', \
     'front_pyramid_stack_height.dat' index 4 using 1:2 with lines lw 1.2 dt 2 lc rgb '#D55E00' title 'ode front', \
     'front_pyramid_stack_height.dat' index 5 using 1:2 with points pt 7 ps 0.5 lc rgb '#009E73' title 'own-impulse', \
     'front_pyramid_stack_height.dat' index 6 using 1:2 with lines lw 1.2 dt 2 lc rgb '#009E73' title 'own-impulse front', \
     'front_pyramid_stack_height.dat' index 7 using 1:2 with points pt 7 ps 0.5 lc rgb '#CC79A7' title 'own-penalty', \
     'front_pyramid_stack_height.dat' index 8 using 1:2 with lines lw 1.2 dt 2 lc rgb '#CC79A7' title 'own-penalty front', \
     'front_pyramid_stack_height.dat' index 9 using 1:2 with lines lw 1.5 lc rgb '#000000' title 'front over all engines'
