#!/usr/bin/env bash
# One work-precision figure for n_a = 3 with both axial-dynamics variants: error against
# rhs evaluations (machine independent) and against wall time, Dynamic (open symbols, the paper's
# model) and QuasiStatic (filled), one colour per integrator, accuracy-controlled points only.
#
# usage: bench/work_precision/plot_axial_dynamics.sh DYNAMIC_RESULTS_CSV QUASI_STATIC_RESULTS_CSV OUT_PNG
# (results.csv files written by bench-work-precision; the committed ones are
#  bench/work_precision/results/results.csv and bench/work_precision/results_qs/results.csv)
set -euo pipefail
dyn=$1 qs=$2 png=$3
command -v gnuplot >/dev/null || { echo "gnuplot is not installed" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
integrators=(rk-merson rk3 rk-feldberg cpodes verlet)
colours=('#1f77b4' '#d62728' '#2ca02c' '#9467bd' '#ff7f0e')
# One data file per variant x integrator: ok accuracy points of n_a = 3, "rhs wall position force".
for variant in dyn qs; do
    csv=$dyn; [ $variant = qs ] && csv=$qs
    python3 - "$csv" "$tmp/$variant" <<'EOF2'
import csv, sys
rows = [r for r in csv.DictReader(open(sys.argv[1])) if r["axial_modes"] == "3" and r["kind"] == "accuracy" and r["status"] == "ok"]
for name in {r["integrator"] for r in rows}:
    with open(f"{sys.argv[2]}-{name}.dat", "w") as f:
        for r in sorted((r for r in rows if r["integrator"] == name), key=lambda r: -float(r["setting"])):
            f.write(f'{r["rhs_evaluations"]} {r["wall_s"]} {r["position_error_m"]} {r["force_error_N"]}\n')
EOF2
done
{
    echo "set terminal png size 1500,1000 font 'DejaVu Sans,10'"
    echo "set output '$png'"
    echo "set grid; set logscale xy; set format x '10^{%L}'; set format y '10^{%L}'"
    echo "set key outside right top font ',9' box"
    echo "set multiplot layout 2,2 title 'Work-precision, n_a = 3, default demo case (20 s): open = Dynamic (axial modes as states), filled = QuasiStatic (condensed)'"
    for panel in "1:3:position error [m]:rhs evaluations" "1:4:payload-end force error [N]:rhs evaluations" \
                 "2:3:position error [m]:wall [s]" "2:4:payload-end force error [N]:wall [s]"; do
        IFS=: read -r xcol ycol ylabel xlabel <<<"$panel"
        echo "set xlabel '$xlabel'; set ylabel '$ylabel'"
        line="plot"
        for i in "${!integrators[@]}"; do
            name=${integrators[$i]} colour=${colours[$i]}
            [ -s "$tmp/dyn-$name.dat" ] && line+=" '$tmp/dyn-$name.dat' using $xcol:$ycol with linespoints pt 6 ps 1.3 lc rgb '$colour' dt 2 title '$name Dynamic',"
            [ -s "$tmp/qs-$name.dat" ] && line+=" '$tmp/qs-$name.dat' using $xcol:$ycol with linespoints pt 7 ps 1.3 lc rgb '$colour' title '$name QuasiStatic',"
        done
        echo "${line%,}"
    done
    echo "unset multiplot"
} >"$tmp/plot.gp"
gnuplot "$tmp/plot.gp"
echo "wrote $png"
