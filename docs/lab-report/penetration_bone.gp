# bone hits the pile: deepest penetration against time: rerun with `gnuplot penetration_bone.gp` in this directory.
set terminal svg size 900,480 dynamic enhanced font 'Helvetica,13' background '#ffffff'
set output 'penetration_bone.svg'
set title 'bone hits the pile: deepest penetration against time' noenhanced
set xlabel 't (s)' noenhanced
set ylabel 'deepest penetration (m)' noenhanced
set grid lc rgb '#dddddd'
set key outside right top noenhanced
set logscale y
set format y '10^{%L}'
plot 'penetration_bone.dat' index 0 using 1:2 with lines lw 1.5 lc rgb '#0072B2' title 'own', \
     'penetration_bone.dat' index 1 using 1:2 with lines lw 1.5 lc rgb '#D55E00' title 'ode', \
     'penetration_bone.dat' index 2 using 1:2 with lines lw 1.5 lc rgb '#009E73' title 'bullet'
