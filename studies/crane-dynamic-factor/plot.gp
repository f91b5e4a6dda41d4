# The study's dynamic factors against EN 13001-2's phi_2 = phi_2,min + beta_2 v_h for the hoisting
# classes HC1..HC4. Reads the runner's results.csv (columns named as the study's parameters and
# metrics: set.payloadMass, hoist-speed, set.initialHookDepth, dynamic_factor, ..., status) and
# writes dynamic_factor_en13001.png next to it:
#   gnuplot -e "results='out/crane-dynamic-factor/results.csv'" studies/crane-dynamic-factor/plot.gp
# (default: results.csv in the current folder). Needs gnuplot 5.
if (!exists("results")) results = 'results.csv'
# Written next to the results: the folder is everything up to results' last '/'.
last = 0
do for [i = 1:strlen(results)] { if (results[i:i] eq '/') { last = i } }
output = (last > 0 ? results[1:last] : '') . 'dynamic_factor_en13001.png'

set terminal pngcairo size 1100,760 font 'DejaVu Sans,11'
set output output
set datafile separator ','
set key outside right top
set grid
set title "Dynamic factor of lifting a grounded load: simulation against EN 13001-2"
set xlabel 'steady hoisting speed v_h [m/s]'
set ylabel 'dynamic factor: peak rope force / static rope force'
set xrange [0:0.65]
set yrange [1:*]

# EN 13001-2, hoisting classes HC1..HC4: phi_2,min and beta_2 [s/m].
phimin(c) = 1.0 + 0.05 * c
beta(c) = 0.17 * c
en(c, v) = phimin(c) + beta(c) * v

# A case's value if it belongs to the series (payload mass m, falls' length h) and ran ok.
ok(m, h) = (strcol("status") eq "ok" && column("set.payloadMass") == m && column("set.initialHookDepth") == h)
pick(m, h) = ok(m, h) ? column("dynamic_factor") : 1/0  # undefined: left out of the line

# The runner writes the cases in study.yaml's order, the first varied parameter slowest: payload
# i (1..3), speed k (1..6), depth j (1..3) is case 18 (i - 1) + 3 (k - 1) + (j - 1), so a series
# (i, j) is every third row from 18 (i - 1) + j - 1. (gnuplot breaks a line at every row a filter
# leaves out; the filter stays, so a failed case is a gap and a reordered study draws no wrong line.)
masses = "2000 5000 10000"
depths = "5 10 20"
first(i, j) = 18 * (i - 1) + (j - 1)
set datafile columnheaders
plot for [c = 1:4] en(c, x) with lines lw 2 dt 2 lc rgb word("#606060 #1f77b4 #2ca02c #d62728", c) \
         title sprintf("EN 13001-2 HC%d: %.2f + %.2f v_h", c, phimin(c), beta(c)), \
     for [i = 1:words(masses)] for [j = 1:words(depths)] results \
         every 3::first(i, j)::first(i, j) + 15 \
         using (column("hoist-speed")):(pick(real(word(masses, i)), real(word(depths, j)))) \
         with linespoints lw 1.5 pt (4 + 2 * (j - 1)) ps 1.2 lc i \
         title sprintf("M = %s kg, h = %s m", word(masses, i), word(depths, j))
