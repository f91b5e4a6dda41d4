# gnuplot -e "dir='...'; png='...'" plot.gp : work-precision of lumped chain vs ALE rope.
set terminal pngcairo size 1500,620 font ",11" noenhanced
set output png
set datafile separator ","
set multiplot layout 1,2 title "Hanging rope (L = 20 m, Table 1, EI = 0), 20 s: lumped-mass chain vs ALE span (Pareto fronts; all runs faint)"
set logscale xy
set grid
set xlabel "wall time of the integration [s]"
set key bottom left font ",9" box opaque
set format y "1e%L"
f = dir."/lumped_chain_runs.csv"
set ylabel "max payload position error [m]"
set title "payload position"
plot f u ((strcol(1) eq "chain" && strcol(5) eq "ok") ? $6 : 1/0):8 w p pt 6 lc rgb "#f4a582" t "chain: all runs", \
     f u ((strcol(1) eq "ale" && strcol(5) eq "ok") ? $6 : 1/0):8 w p pt 6 lc rgb "#92c5de" t "ALE: all runs", \
     dir."/front_chain_pos.dat" u 1:2 w lp pt 7 lw 2 lc rgb "#b2182b" t "chain (N = 5...50) Pareto front", \
     dir."/front_ale_pos.dat" u 1:2 w lp pt 7 lw 2 lc rgb "#2166ac" t "ALE (n_a = 0...8, n_t = 1...4) Pareto front"
set ylabel "max payload-end axial force error [N]"
set title "axial force at the payload end"
set key top right
set yrange [1e-3:1e3]
plot f u ((strcol(1) eq "chain" && strcol(5) eq "ok") ? $6 : 1/0):9 w p pt 6 lc rgb "#f4a582" t "chain: all runs", \
     f u ((strcol(1) eq "ale" && strcol(5) eq "ok") ? $6 : 1/0):9 w p pt 6 lc rgb "#92c5de" t "ALE: all runs", \
     dir."/front_chain_force.dat" u 1:2 w lp pt 7 lw 2 lc rgb "#b2182b" t "chain Pareto front", \
     f u ((strcol(1) eq "ale" && strcol(5) eq "ok") ? $6 : 1/0):11 w p pt 4 lc rgb "#a6dba0" t "ALE from the node force: all runs", \
     dir."/front_ale_force.dat" u 1:2 w lp pt 7 lw 2 lc rgb "#2166ac" t "ALE, EA eps at s = L: Pareto front", \
     dir."/front_ale_nodeforce.dat" u 1:2 w lp pt 5 lw 2 lc rgb "#1b7837" t "ALE, from getNodeForce: Pareto front", \
     0.022 w l dt 2 lw 2 lc rgb "black" t "uncertainty of the force reference (0.022 N)"
unset multiplot
