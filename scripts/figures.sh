#!/usr/bin/env bash
# Regenerates the figures README.md shows, from the bundled demos' default runs, into docs/:
#   fig2..fig5_*.png                   reeving-pendulum (the paper's Table 1 study, n_a = 0..3)
#   crane_snapshots.png, crane_hook_height_sway.png, crane_fall_axial_forces.png, crane_energy.png
#                                      reeving-crane (the default lift-traverse-lower cycle)
#   elevator_emergency_stop.png, elevator_emergency_stop_machine.png
#                                      reeving-elevator --scenario emergency-stop
#   crane_cycle.gif                    scripts/crane-animation.sh
# usage: scripts/figures.sh [BUILD_DIR]   (default build, configured by ./scripts/demo.sh or
#        ./scripts/build.sh); builds the three demos there. Needs gnuplot (gnuplot-nox).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build}
docs=$root/docs
command -v gnuplot > /dev/null || { echo "figures.sh: gnuplot not found (apt-get install gnuplot-nox)" >&2; exit 1; }
cmake --build "$build" --target reeving-pendulum reeving-crane reeving-elevator > /dev/null
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$build/examples/reeving-pendulum" --quiet --out "$work/pendulum" > /dev/null
cp "$work"/pendulum/fig[2-5]_*.png "$docs/"
"$build/examples/reeving-crane" --quiet --out "$work/crane" > /dev/null
for f in snapshots hook_height_sway fall_axial_forces energy; do
    cp "$work/crane/fig_$f.png" "$docs/crane_$f.png"
done
"$build/examples/reeving-elevator" --quiet --scenario emergency-stop --out "$work/elevator" > /dev/null
cp "$work/elevator/elevator_emergency-stop.png" "$docs/elevator_emergency_stop.png"
cp "$work/elevator/elevator_emergency-stop_machine.png" "$docs/elevator_emergency_stop_machine.png"
"$root/scripts/crane-animation.sh" "$build" "$docs/crane_cycle.gif"
echo "figures.sh: figures written to $docs"
