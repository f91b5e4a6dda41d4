#!/usr/bin/env bash
# Regenerates the figures README.md shows, from the bundled demos' default runs, into docs/:
#   fig2_payload_displacement.png, fig3_static_axial_force.png, fig4_payload_end_axial_force.png,
#   fig5_axial_force_difference.png   reeving-pendulum (the paper's Table 1 study, n_a = 0..3)
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
for f in fig2_payload_displacement.png fig3_static_axial_force.png fig4_payload_end_axial_force.png \
         fig5_axial_force_difference.png; do
    cp "$work/pendulum/$f" "$docs/$f"
done
# Reverse bends weighted 2 for docs/rope-life.md's figure (the weight changes only the bending count).
"$build/examples/reeving-crane" --reverse-bend-factor 2 --quiet --out "$work/crane" > /dev/null
cp "$work/crane/fig_snapshots.png" "$docs/crane_snapshots.png"
cp "$work/crane/fig_hook_height_sway.png" "$docs/crane_hook_height_sway.png"
cp "$work/crane/fig_fall_axial_forces.png" "$docs/crane_fall_axial_forces.png"
cp "$work/crane/fig_energy.png" "$docs/crane_energy.png"
cp "$work/crane/fig_rope_bending.png" "$docs/crane_rope_bending.png"
"$build/examples/reeving-elevator" --quiet --scenario emergency-stop --out "$work/elevator" > /dev/null
cp "$work/elevator/elevator_emergency-stop.png" "$docs/elevator_emergency_stop.png"
cp "$work/elevator/elevator_emergency-stop_machine.png" "$docs/elevator_emergency_stop_machine.png"
"$root/scripts/crane-animation.sh" "$build" "$docs/crane_cycle.gif"
echo "figures.sh: figures written to $docs"
