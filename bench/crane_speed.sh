#!/usr/bin/env bash
# Real-time factor of the reeving-crane demo: the default cycle (4 falls,
# 36 s: lift 5 m, traverse 10 m, lower 5 m) and a 12-fall variant, each with n_a = 0 and 1
# (QuasiStatic axial modes, n_t = 1, RK-Merson 1e-6, reports every 0.02 s: the demo's defaults).
# Builds the Release demo, runs every configuration REPEATS times (interleaved) pinned to one
# core, and prints the medians as a Markdown table. Real-time factor = simulated time / wall time
# of the simulation loop (summary.json "real_time_factor": static equilibrium, output files and
# figures excluded); the process wall time (everything but the figures) is printed too.
#
# usage: bench/crane_speed.sh [REPEATS] [BUILD_DIR]     (defaults 3, build)
set -euo pipefail
cd "$(dirname "$0")/.."
n=${1:-3}
build=${2:-build}
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" -j"$(nproc)" --target reeving-crane >/dev/null
bin="$build/examples/reeving-crane"
pin=()
command -v taskset >/dev/null 2>&1 && pin=(taskset -c 0)
CONFIGS=(
    "default cycle, 4 falls, n_a = 0|--falls 4 --axial-modes 0"
    "default cycle, 4 falls, n_a = 1|--falls 4 --axial-modes 1"
    "12 falls, n_a = 0|--falls 12 --axial-modes 0"
    "12 falls, n_a = 1|--falls 12 --axial-modes 1"
)
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
for i in $(seq "$n"); do
    for c in "${!CONFIGS[@]}"; do
        IFS='|' read -r label opts <<<"${CONFIGS[$c]}"
        start=$(date +%s.%N)
        # shellcheck disable=SC2086
        "${pin[@]}" "$bin" $opts --no-plots --quiet --out "$out/run" >/dev/null
        end=$(date +%s.%N)
        python3 - "$out/run/summary.json" "$c" "$start" "$end" >>"$out/runs.txt" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
print(sys.argv[2], s["real_time_factor"], s["wall_seconds"], float(sys.argv[4]) - float(sys.argv[3]), s["steps"],
      s["rhs_evaluations"], s["t_reached"], s["energy_residual_relative"])
PY
    done
done
python3 - "$out/runs.txt" "$n" "${CONFIGS[@]}" <<'PY'
import statistics, sys
rows = [l.split() for l in open(sys.argv[1])]
n = sys.argv[2]
labels = [c.split("|")[0] for c in sys.argv[3:]]
print(f"| configuration | steps | rhs | loop wall [s] | real-time factor | process wall [s] | us per rhs | energy residual / work |")
print("|---|---:|---:|---:|---:|---:|---:|---:|")
for c, label in enumerate(labels):
    rs = [r for r in rows if int(r[0]) == c]
    rtf = statistics.median(float(r[1]) for r in rs)
    loop = statistics.median(float(r[2]) for r in rs)
    proc = statistics.median(float(r[3]) for r in rs)
    steps, rhs, res = int(rs[0][4]), int(rs[0][5]), float(rs[0][7])
    print(f"| {label} | {steps} | {rhs} | {loop:.2f} | {rtf:.1f}x | {proc:.2f} | {1e6 * loop / rhs:.0f} | {res:.1e} |")
print(f"\n(median of {n} runs each, one core)")
PY
