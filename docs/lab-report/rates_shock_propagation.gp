# bone_hits_pile, shock propagation: residual after each pass at single steps (dotted: the fitted line): rerun with `gnuplot rates_shock_propagation.gp` in this directory.
set terminal svg size 1000,640 dynamic enhanced font 'Helvetica,13' background '#ffffff'
set output 'rates_shock_propagation.svg'
set title 'bone_hits_pile, shock propagation: residual after each pass at single steps (dotted: the fitted line)' noenhanced
set xlabel 'pass' noenhanced
set ylabel 'largest velocity change (m/s)' noenhanced
set grid lc rgb '#dddddd'
set key outside right top noenhanced
set logscale y
set format y '10^{%L}'
set key below left Left reverse
set xrange [0.5:20.5]
set xtics 1
set yrange [1e-14:*]
plot 'rates_shock_propagation.dat' index 0 using 1:2 with linespoints lw 1.5 pt 7 ps 0.7 lc rgb '#0072B2' title 'ours, t = 1.846 s (largest pass 1): factor 0.549 a pass', \
     'rates_shock_propagation.dat' index 1 using 1:2 with lines lw 1 dt 3 lc rgb '#0072B2' notitle, \
     'rates_shock_propagation.dat' index 2 using 1:2 with linespoints lw 1.5 pt 4 ps 0.7 lc rgb '#0072B2' title 'ours, t = 2.700 s (median step): factor 0.306 a pass', \
     'rates_shock_propagation.dat' index 3 using 1:2 with lines lw 1 dt 3 lc rgb '#0072B2' notitle, \
     'rates_shock_propagation.dat' index 4 using 1:2 with linespoints lw 1.5 pt 7 ps 0.7 lc rgb '#009E73' title 'lab + shock propagation, t = 1.988 s (largest pass 1): factor 0.234 a pass', \
     'rates_shock_propagation.dat' index 5 using 1:2 with lines lw 1 dt 3 lc rgb '#009E73' notitle, \
     'rates_shock_propagation.dat' index 6 using 1:2 with linespoints lw 1.5 pt 4 ps 0.7 lc rgb '#009E73' title 'lab + shock propagation, t = 2.433 s (median step): factor 0.214 a pass', \
     'rates_shock_propagation.dat' index 7 using 1:2 with lines lw 1 dt 3 lc rgb '#009E73' notitle, \
     1e-13 with lines lw 1 dt 2 lc rgb '#777777' title 'rounding floor (not fitted)'
