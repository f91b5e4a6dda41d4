#!/usr/bin/env bash
# Prints the numbers the documents quote (docs/verification.md) from the bundled demos' default runs
# (one run each):
#   pendulum (reeving-pendulum defaults: n_a = 0..3, quasi-static, 20 s): steps and wall per case,
#     the largest payload x difference from n_a = 0 (Fig 2), the mean payload-end axial force
#     below n_a = 0's (Fig 4/5), the largest energy drift / KE0;
#   the same demo with --axial-dynamics dynamic (the paper's model; about 15 s of wall): steps and
#     wall of its n_a = 3 case and of the whole demo, against the default's;
#   the same demo with --axial-law linear (the paper's law): the largest payload position and
#     payload-end axial force differences from the default (tension-only) run, n_a = 1 and 3;
#   crane (reeving-crane defaults: 4 falls, n_a = 1): the largest |energy residual| and its ratio
#     to the drives' largest work, steps, wall, real-time factor;
#   the lumped-chain comparison's speed ratios (docs/performance.md), from the sweep's table
#     bench/lumped_chain/results/lumped_chain_runs.csv (`bench-lumped-chain ratios`, no runs).
# usage: bench/readme_figures.sh [--no-build] [BUILD_DIR]   (default build; builds the two demos and
#        bench-lumped-chain there unless --no-build)
set -euo pipefail
cd "$(dirname "$0")/.."
buildFirst=1
if [[ ${1:-} == --no-build ]]; then buildFirst=0; shift; fi
build=${1:-build}
[[ $buildFirst == 0 ]] || cmake --build "$build" --target reeving-pendulum reeving-crane bench-lumped-chain > /dev/null
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
now() { date +%s.%N; }
t0=$(now)
"$build/examples/reeving-pendulum" --no-plots --quiet --out "$out/pendulum" > /dev/null
t1=$(now)
"$build/examples/reeving-pendulum" --axial-dynamics dynamic --no-plots --quiet --out "$out/pendulum-dynamic" > /dev/null
t2=$(now)
"$build/examples/reeving-pendulum" --axial-law linear --no-plots --quiet --out "$out/pendulum-linear" > /dev/null
t3=$(now)
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
q="$out/pendulum/modes-3/summary.json"
d="$out/pendulum-dynamic/modes-3/summary.json"
echo "pendulum with --axial-dynamics dynamic, against the default quasi-static run"
awk -v qs="$(num "$q" steps)" -v ds="$(num "$d" steps)" -v qw="$(num "$q" wall_seconds)" -v dw="$(num "$d" wall_seconds)" \
    -v qd="$(awk -v a="$t0" -v b="$t1" 'BEGIN{print b - a}')" -v dd="$(awk -v a="$t1" -v b="$t2" 'BEGIN{print b - a}')" \
    'BEGIN { printf "  n_a = 3: %d steps dynamic, %d quasi-static (%.0fx); case wall %.2f s dynamic, %.2f s quasi-static (%.0fx)\n", ds, qs, ds / qs, dw, qw, dw / qw
             printf "  whole demo (four cases): %.1f s of wall dynamic, %.1f s quasi-static\n", dd, qd }'
echo "pendulum with --axial-law linear, against the default tension-only run"
for na in 1 3; do
    paste -d, "$out/pendulum/modes-$na/timeseries.csv" "$out/pendulum-linear/modes-$na/timeseries.csv" |
        awk -F, -v na=$na 'NR == 1 { n = NF / 2; for (i = 1; i <= n; ++i) col[$i] = i; next }
            { dx = $col["x"] - $(n + col["x"]); dy = $col["y"] - $(n + col["y"]); d = sqrt(dx * dx + dy * dy)
              f = $col["axial_force_payload"] - $(n + col["axial_force_payload"]); if (f < 0) f = -f
              if (d > dmax) dmax = d; if (f > fmax) fmax = f; P = $col["axial_force_payload"] }
            END { printf "  n_a = %d: payload within %.2g m, payload-end axial force within %.2g N (of %.0f N)\n", na, dmax, fmax, P }'
done
awk -v a="$t1" -v b="$t2" -v c="$t3" -v d="$t0" 'BEGIN { printf "  whole demo (four cases): %.2f s of wall linear, %.2f s tension-only\n", c - b, a - d }'
s="$out/crane/summary.json"
echo "crane (reeving-crane defaults)"
grep -o '"[a-zA-Z_]*\(energy_residual\|motion_work\|steps\|wall_seconds\|real_time_factor\)[a-zA-Z_]*": *[-0-9.eE+]*' "$s" | sed 's/^/  /'
echo "lumped-mass chain against the ALE rope (bench-lumped-chain ratios, from the sweep's table)"
mkdir -p "$out/lumped-chain"
"$build/bench/bench-lumped-chain" ratios bench/lumped_chain/results/lumped_chain_runs.csv --out-dir "$out/lumped-chain" |
    grep -E '^(pos error 1e-0[56]|force error 1:)' | sed 's/^/  /'
