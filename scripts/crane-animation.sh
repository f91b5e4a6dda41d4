#!/usr/bin/env bash
# Animation of the crane's lift-traverse-lower cycle for readers without a display: the
# reeving-crane demo's default cycle drawn every 0.5 s of its 36 s (crane-animation-frames, the
# demo's scene, settings and drawing) and animated with gnuplot's gif terminal (0.1 s a frame:
# 5x real time).
#   scripts/crane-animation.sh [BUILD_DIR [OUT.gif]]   (defaults: build, docs/crane_cycle.gif)
# Builds the crane-animation-frames target in BUILD_DIR (configured already); needs gnuplot.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build}
out=${2:-$root/docs/crane_cycle.gif}
command -v gnuplot > /dev/null || { echo "crane-animation: gnuplot not found (apt-get install gnuplot-nox)" >&2; exit 1; }
cmake --build "$build" --target crane-animation-frames > /dev/null
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$build/examples/crane-animation-frames" "$work/frames.dat" 0.5
frames=$(grep -c '^# snapshot' "$work/frames.dat")
mkdir -p "$(dirname "$out")"
# Inks (examples/crane/CraneFigures.h): 1 structure, 2 trolley, 3 drum, 4 sheave, 5 rope,
# 6 hook block, 7 payload; the same colours as the demo's figures.
gnuplot <<GP
set terminal gif animate delay 10 loop 0 size 480,420 font 'DejaVu Sans,9'
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
  set title sprintf('reeving-crane: lift 5 m, traverse 10 m, lower   t = %4.1f s', i * 0.5)
  plot '$work/frames.dat' index i using 1:2:3 with lines lc variable
}
GP
echo "crane-animation: wrote $out ($frames frames, $(du -k "$out" | cut -f1) kB)"
