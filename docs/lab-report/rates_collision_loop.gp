# bone_hits_pile, collision loop: residual after each pass at single steps (dotted: the fitted line): rerun with `gnuplot rates_collision_loop.gp` in this directory.
set terminal svg size 1000,640 dynamic enhanced font 'Helvetica,13' background '#ffffff'
set output 'rates_collision_loop.svg'
set title 'bone_hits_pile, collision loop: residual after each pass at single steps (dotted: the fitted line)' noenhanced
set xlabel 'pass' noenhanced
set ylabel 'largest approaching normal velocity (m/s)' noenhanced
set grid lc rgb '#dddddd'
set key outside right top noenhanced
set logscale y
set format y '10^{%L}'
set key below left Left reverse
set xrange [0.5:5.5]
set xtics 1
set yrange [4.06576e-21:*]
plot 'rates_collision_loop.dat' index 0 using 1:2 with linespoints lw 1.5 pt 7 ps 0.7 lc rgb '#0072B2' title 'ours, t = 1.846 s (largest pass 1): factor 0.526 a pass', \
     'rates_collision_loop.dat' index 1 using 1:2 with lines lw 1 dt 3 lc rgb '#0072B2' notitle, \
     'rates_collision_loop.dat' index 2 using 1:2 with linespoints lw 1.5 pt 4 ps 0.7 lc rgb '#0072B2' title 'ours, t = 2.900 s (median step): factor 0.257 a pass', \
     'rates_collision_loop.dat' index 3 using 1:2 with lines lw 1 dt 3 lc rgb '#0072B2' notitle, \
     'rates_collision_loop.dat' index 4 using 1:2 with linespoints lw 1.5 pt 7 ps 0.7 lc rgb '#D55E00' title 'lab, t = 1.854 s (largest pass 1): factor 0.618 a pass', \
     'rates_collision_loop.dat' index 5 using 1:2 with lines lw 1 dt 3 lc rgb '#D55E00' notitle, \
     'rates_collision_loop.dat' index 6 using 1:2 with linespoints lw 1.5 pt 4 ps 0.7 lc rgb '#D55E00' title 'lab, t = 2.921 s (median step): factor 0.18 a pass', \
     'rates_collision_loop.dat' index 7 using 1:2 with lines lw 1 dt 3 lc rgb '#D55E00' notitle, \
     'rates_collision_loop.dat' index 8 using 1:2 with linespoints lw 1.5 pt 7 ps 0.7 lc rgb '#009E73' title 'lab + shock propagation, t = 1.854 s (largest pass 1): factor 0.37 a pass', \
     'rates_collision_loop.dat' index 9 using 1:2 with lines lw 1 dt 3 lc rgb '#009E73' notitle, \
     'rates_collision_loop.dat' index 10 using 1:2 with linespoints lw 1.5 pt 4 ps 0.7 lc rgb '#009E73' title 'lab + shock propagation, t = 1.863 s (median step): factor 0.246 a pass', \
     'rates_collision_loop.dat' index 11 using 1:2 with lines lw 1 dt 3 lc rgb '#009E73' notitle, \
     1e-13 with lines lw 1 dt 2 lc rgb '#777777' title 'rounding floor (not fitted)'
