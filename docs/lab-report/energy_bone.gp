# bone_hits_pile, ours: energy against time, collision events marked: rerun with `gnuplot energy_bone.gp` in this directory.
set terminal svg size 900,480 dynamic enhanced font 'Helvetica,13' background '#ffffff'
set output 'energy_bone.svg'
set title 'bone_hits_pile, ours: energy against time, collision events marked' noenhanced
set xlabel 't (s)' noenhanced
set ylabel 'energy (J)' noenhanced
set grid lc rgb '#dddddd'
set key outside right top noenhanced
plot 'energy_bone.dat' index 0 using 1:2 with lines lw 1.5 lc rgb '#0072B2' title 'translational', \
     'energy_bone.dat' index 1 using 1:2 with lines lw 1.5 lc rgb '#D55E00' title 'rotational', \
     'energy_bone.dat' index 2 using 1:2 with lines lw 1.5 lc rgb '#009E73' title 'potential - potential(0)', \
     'energy_bone.dat' index 3 using 1:2 with lines lw 1.5 lc rgb '#CC79A7' title 'total - total(0)', \
     'energy_bone.dat' index 4 using 1:2 with points pt 2 ps 0.8 lc rgb '#000000' title 'collision events'
