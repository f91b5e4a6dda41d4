#!/usr/bin/env bash
# Animation of the crane's lift-traverse-lower cycle for readers without a display:
# runs reeving-crane headless (its 12 rope-geometry snapshots, the most --snapshots allows, evenly
# over the 36 s cycle: every 3.27 s) and draws them with gnuplot's gif terminal, 0.6 s a frame.
#   scripts/crane-animation.sh [BUILD_DIR [OUT.gif]]   (defaults: build, docs/crane_cycle.gif)
# Needs a built reeving-crane (cmake --build BUILD_DIR --target reeving-crane) and gnuplot.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build}
out=${2:-$root/docs/crane_cycle.gif}
exe=$build/examples/reeving-crane
[ -x "$exe" ] || { echo "crane-animation: $exe not found; build it: cmake --build $build --target reeving-crane" >&2; exit 1; }
command -v gnuplot > /dev/null || { echo "crane-animation: gnuplot not found (apt-get install gnuplot-nox)" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
frames=12  # t = 0, 3.27, ..., 36 s
"$exe" --snapshots $frames --no-plots --quiet --out "$work/crane" > "$work/run.log"
mkdir -p "$(dirname "$out")"
# Inks of snapshots.dat (examples/crane/CraneFigures.h): 1 structure, 2 trolley, 3 drum, 4 sheave,
# 5 rope, 6 hook block, 7 payload.
gnuplot <<GP
set terminal gif animate delay 60 loop 0 size 560,480 font 'DejaVu Sans,10'
set output '$out'
set size ratio -1
set xrange [-4:14]
set yrange [-0.5:16.5]
unset key
set xlabel 'x [m]'
set ylabel 'y [m]'
set linetype 1 lc rgb '#909090' lw 1.5
set linetype 2 lc rgb '#1f5fa8' lw 2
set linetype 3 lc rgb '#d07000' lw 2
set linetype 4 lc rgb '#7030a0' lw 1
set linetype 5 lc rgb '#101010' lw 1
set linetype 6 lc rgb '#1f5fa8' lw 2
set linetype 7 lc rgb '#2a8a2a' lw 2
do for [i=0:$frames-1] {
  set title sprintf('reeving-crane: lift 5 m, traverse 10 m, lower; t = %.1f s', i * 36.0 / ($frames - 1))
  plot '$work/crane/snapshots.dat' index i using 1:2:3 with lines lc variable
}
GP
echo "crane-animation: wrote $out ($(du -k "$out" | cut -f1) kB)"
