# yaw45_octagon: 8 contact points and normals (ours): rerun with `gnuplot contacts_yaw45_octagon.gp` in this directory.
set terminal svg size 640,560 dynamic enhanced font 'Helvetica,13' background '#ffffff'
set output 'contacts_yaw45_octagon.svg'
set title 'yaw45_octagon: 8 contact points and normals (ours)' noenhanced
set xlabel 'x (m)' noenhanced
set ylabel 'y (m)' noenhanced
set grid lc rgb '#dddddd'
set key outside right top noenhanced
unset title
set label 1 'yaw45_octagon: 8 contact points and normals (ours)' at screen 0.5, 0.965 center noenhanced
set tmargin 4
set zlabel 'z (m)' rotate parallel
set view 68, 28
set view equal xyz
set xyplane 0
splot 'contacts_yaw45_octagon.dat' index 0 using 1:2:3:4:5:6 with vectors nohead lw 1.2 lc rgb '#0072B2' title 'box A', \
      'contacts_yaw45_octagon.dat' index 1 using 1:2:3:4:5:6 with vectors nohead lw 1.2 lc rgb '#777777' title 'box B', \
      'contacts_yaw45_octagon.dat' index 2 using 1:2:3 with points pt 7 ps 0.8 lc rgb '#D55E00' title 'contact points', \
      'contacts_yaw45_octagon.dat' index 3 using 1:2:3:4:5:6 with vectors head filled lw 1.5 lc rgb '#009E73' title 'normals'
