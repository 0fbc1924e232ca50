# stack_10: stack_height against solver iterations: rerun with `gnuplot iterations_stack_10_stack_height.gp` in this directory.
set terminal svg size 900,440 dynamic enhanced font 'Helvetica,13' background '#ffffff'
set output 'iterations_stack_10_stack_height.svg'
set title 'stack_10: stack_height against solver iterations' noenhanced
set xlabel 'iterations' noenhanced
set ylabel 'stack_height (m)' noenhanced
set grid lc rgb '#dddddd'
set key outside below center horizontal maxcols 4 noenhanced
set datafile missing 'NaN'
set logscale x
set format x '10^{%L}'
set logscale y
set format y '10^{%L}'
plot 'iterations_stack_10_stack_height.dat' index 0 using 1:2 with linespoints lw 1.5 dt 1 pt 7 ps 0.7 lc rgb '#009E73' title 'bullet dt=0.004167', \
     'iterations_stack_10_stack_height.dat' index 1 using 1:2 with linespoints lw 1.5 dt 1 pt 7 ps 0.7 lc rgb '#D55E00' title 'ode dt=0.004167'
