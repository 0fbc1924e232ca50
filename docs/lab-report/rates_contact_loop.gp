# bone_hits_pile, contact loop: residual after each pass at single steps (dotted: the fitted line): rerun with `gnuplot rates_contact_loop.gp` in this directory.
set terminal svg size 1000,640 dynamic enhanced font 'Helvetica,13' background '#ffffff'
set output 'rates_contact_loop.svg'
set title 'bone_hits_pile, contact loop: residual after each pass at single steps (dotted: the fitted line)' noenhanced
set xlabel 'pass' noenhanced
set ylabel 'largest approaching normal velocity (m/s)' noenhanced
set grid lc rgb '#dddddd'
set key outside right top noenhanced
set logscale y
set format y '10^{%L}'
set key below left Left reverse
set xrange [0.5:10.5]
set xtics 1
plot 'rates_contact_loop.dat' index 0 using 1:2 with linespoints lw 1.5 pt 7 ps 0.7 lc rgb '#0072B2' title 'ours, t = 1.829 s (largest pass 1): factor 0.853 a pass', \
     'rates_contact_loop.dat' index 1 using 1:2 with lines lw 1 dt 3 lc rgb '#0072B2' notitle, \
     'rates_contact_loop.dat' index 2 using 1:2 with linespoints lw 1.5 pt 4 ps 0.7 lc rgb '#0072B2' title 'ours, t = 2.888 s (median step): factor 0.808 a pass', \
     'rates_contact_loop.dat' index 3 using 1:2 with lines lw 1 dt 3 lc rgb '#0072B2' notitle, \
     'rates_contact_loop.dat' index 4 using 1:2 with linespoints lw 1.5 pt 7 ps 0.7 lc rgb '#D55E00' title 'lab, t = 1.967 s (largest pass 1): factor 0.945 a pass', \
     'rates_contact_loop.dat' index 5 using 1:2 with lines lw 1 dt 3 lc rgb '#D55E00' notitle, \
     'rates_contact_loop.dat' index 6 using 1:2 with linespoints lw 1.5 pt 4 ps 0.7 lc rgb '#D55E00' title 'lab, t = 2.554 s (median step): factor 0.64 a pass', \
     'rates_contact_loop.dat' index 7 using 1:2 with lines lw 1 dt 3 lc rgb '#D55E00' notitle, \
     'rates_contact_loop.dat' index 8 using 1:2 with linespoints lw 1.5 pt 7 ps 0.7 lc rgb '#009E73' title 'lab + shock propagation, t = 1.988 s (largest pass 1): factor 0.971 a pass', \
     'rates_contact_loop.dat' index 9 using 1:2 with lines lw 1 dt 3 lc rgb '#009E73' notitle, \
     'rates_contact_loop.dat' index 10 using 1:2 with linespoints lw 1.5 pt 4 ps 0.7 lc rgb '#009E73' title 'lab + shock propagation, t = 1.846 s (median step): factor 0.854 a pass', \
     'rates_contact_loop.dat' index 11 using 1:2 with lines lw 1 dt 3 lc rgb '#009E73' notitle
