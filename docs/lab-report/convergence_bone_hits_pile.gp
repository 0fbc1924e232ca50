# bone_hits_pile.json: residual after each pass (mean over the run): rerun with `gnuplot convergence_bone_hits_pile.gp` in this directory.
set terminal svg size 900,480 dynamic enhanced font 'Helvetica,13' background '#ffffff'
set output 'convergence_bone_hits_pile.svg'
set title 'bone_hits_pile.json: residual after each pass (mean over the run)' noenhanced
set xlabel 'pass' noenhanced
set ylabel 'largest approaching normal velocity (m/s)' noenhanced
set grid lc rgb '#dddddd'
set key outside right top noenhanced
set datafile missing 'NaN'
set logscale y
set format y '10^{%L}'
plot 'convergence_bone_hits_pile.dat' index 0 using 1:2 with linespoints lw 1.5 pt 7 ps 0.7 lc rgb '#0072B2' title 'collision loop', \
     'convergence_bone_hits_pile.dat' index 1 using 1:2 with linespoints lw 1.5 pt 7 ps 0.7 lc rgb '#D55E00' title 'contact loop', \
     'convergence_bone_hits_pile.dat' index 2 using 1:2 with linespoints lw 1.5 pt 7 ps 0.7 lc rgb '#009E73' title 'shock propagation (largest change)', \
     0.00353369746 with lines lw 1 dt 3 lc rgb '#777777' title 'after shock'
