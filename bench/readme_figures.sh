#!/usr/bin/env bash
# Prints the figures README.md quotes from the two bundled demos' default runs (one run each):
#   pendulum (reeving-pendulum defaults: n_a = 0..3, quasi-static, 20 s): steps and wall per case,
#     the largest payload x difference from n_a = 0 (Fig 2), the mean payload-end axial force
#     below n_a = 0's (Fig 4/5), the largest energy drift / KE0;
#   crane (reeving-crane defaults: 4 falls, n_a = 1): the largest |energy residual| and its ratio
#     to the drives' largest work, steps, wall, real-time factor.
# usage: bench/readme_figures.sh [BUILD_DIR]   (default build; builds the two demos there)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
cmake --build "$build" --target reeving-pendulum reeving-crane > /dev/null
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
"$build/examples/reeving-pendulum" --no-plots --quiet --out "$out/pendulum" > /dev/null
"$build/examples/reeving-crane" --no-plots --quiet --out "$out/crane" > /dev/null
num() { grep -o "\"$2\": *[-0-9.eE+]*" "$1" | head -1 | sed 's/.*: *//'; }
echo "pendulum (reeving-pendulum defaults)"
for na in 0 1 2 3; do
    s="$out/pendulum/modes-$na/summary.json"
    printf "  n_a = %d: %s steps, %s s wall, max |E - E0| / KE0 = %s\n" "$na" "$(num "$s" steps)" \
        "$(num "$s" wall_seconds)" \
        "$(awk -v a="$(num "$s" max_energy_drift_J)" -v b="$(num "$s" initial_kinetic_energy_J)" 'BEGIN{printf "%.2g", a/b}')"
done
awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) col[$i] = i; next }
         { for (n = 1; n <= 3; ++n) {
               d = $col["x_" n] - $col["x_0"]; if (d < 0) d = -d; if (d > dx[n]) dx[n] = d
               df[n] += $col["axial_force_payload_0"] - $col["axial_force_payload_" n] }
           rows++ }
         END { for (n = 1; n <= 3; ++n)
                   printf "  n_a = %d vs 0: payload x within %.3g m; payload-end axial force %.1f N lower on average\n",
                          n, dx[n], df[n] / rows }' "$out/pendulum/comparison.csv"
s="$out/crane/summary.json"
echo "crane (reeving-crane defaults)"
grep -o '"[a-zA-Z_]*\(energy_residual\|motion_work\|steps\|wall_seconds\|real_time_factor\)[a-zA-Z_]*": *[-0-9.eE+]*' "$s" | sed 's/^/  /'
