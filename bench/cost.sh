#!/usr/bin/env bash
# Cost per right-hand side of the two demos against Simbody's own floor (the scenes without ropes), in one
# run, as one Markdown table:
#   pendulum: reeving-pendulum --axial-modes 3 (the demo's default case: quasi-static axial modes,
#             n_t = 1, RK-Merson 1e-6, reports every 0.01 s) against bench-floor-pendulum;
#   crane:    reeving-crane --falls 12 --axial-modes 1 --sheaves point (the floor's geometry: falls
#             between sheave centres; RK-Merson 1e-6, reports every 0.02 s)
#             against bench-floor-crane (12 falls);
# the floors are the same scenes with massless Force::TwoPointLinearSpring's in place of the rope
# (bench/floor/*.cpp say what is the same and what is not).
# Columns, plugin | floor | ratio plugin / floor for each:
#   instructions per rhs: callgrind totals of two runs of different length, (I2 - I1) / (rhs2 - rhs1)
#     (start-up, static equilibrium and output cancel; reports are included), t-end 1 s and 2 s
#     (pendulum), 1.5 s and 3 s (crane); rhs = summary.json "rhs_evaluations";
#   rhs per simulated second and steps: of the full-length runs (pendulum 20 s, crane 36 s);
#   process wall: the full-length runs pinned to one core (taskset -c CORE), interleaved
#     plugin / floor / plugin / floor ..., median of REPEATS; the demos with --no-plots --quiet,
#     both sides writing their outputs to a temporary folder.
# Builds the four targets in BUILD_DIR first (configures it as Release if it is not configured).
# Takes about 5 minutes of CPU (2.5 under callgrind, most of it the plugin's crane; the walls:
# about 37 s per repeat on an idle core).
#
# usage: bench/cost.sh [BUILD_DIR]       (default build; environment: REPEATS=5, CORE=1)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
repeats=${REPEATS:-5}
core=${CORE:-1}
command -v valgrind >/dev/null || { echo "cost.sh: valgrind not found" >&2; exit 1; }
command -v taskset >/dev/null || { echo "cost.sh: taskset not found" >&2; exit 1; }
[ -f "$build/CMakeCache.txt" ] || cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" -j2 --target reeving-pendulum reeving-crane bench-floor-pendulum bench-floor-crane >/dev/null

# name | command | callgrind t-end 1 | t-end 2 | full t-end
CASES=(
    "pendulum-plugin|$build/examples/reeving-pendulum --axial-modes 3 --no-plots --quiet|1|2|20"
    "pendulum-floor|$build/bench/bench-floor-pendulum --quiet|1|2|20"
    "crane-plugin|$build/examples/reeving-crane --falls 12 --axial-modes 1 --sheaves point --no-plots --quiet|1.5|3|36"
    "crane-floor|$build/bench/bench-floor-crane --falls 12 --quiet|1.5|3|36"
)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
rhs() { python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["rhs_evaluations"])' "$1/summary.json"; }

# Instructions per rhs (callgrind: deterministic).
for c in "${CASES[@]}"; do
    IFS='|' read -r name cmd t1 t2 _ <<<"$c"
    for t in "$t1" "$t2"; do
        # shellcheck disable=SC2086
        if ! valgrind --tool=callgrind --callgrind-out-file="$tmp/cg.out" $cmd --t-end "$t" --out "$tmp/$name-$t" \
            >/dev/null 2>"$tmp/cg.log"; then
            echo "cost.sh: $cmd --t-end $t failed under callgrind:" >&2
            cat "$tmp/cg.log" >&2
            exit 1
        fi
        instructions=$(sed -n 's/.*Collected : \([0-9]*\).*/\1/p' "$tmp/cg.log")
        echo "$name $t $instructions $(rhs "$tmp/$name-$t")" >>"$tmp/callgrind.txt"
    done
done

# Process walls, pinned and interleaved, at the full length.
for _ in $(seq "$repeats"); do
    for c in "${CASES[@]}"; do
        IFS='|' read -r name cmd _ _ tfull <<<"$c"
        start=$(date +%s.%N)
        # shellcheck disable=SC2086
        taskset -c "$core" $cmd --t-end "$tfull" --out "$tmp/$name-full" >/dev/null
        end=$(date +%s.%N)
        python3 - "$tmp/$name-full/summary.json" "$name" "$start" "$end" "$tfull" >>"$tmp/walls.txt" <<'PY'
import json, sys
s = json.load(open(sys.argv[1]))
print(sys.argv[2], float(sys.argv[4]) - float(sys.argv[3]), s["rhs_evaluations"], s["steps"], sys.argv[5])
PY
    done
done

python3 - "$tmp/callgrind.txt" "$tmp/walls.txt" "$repeats" "$core" <<'PY'
import statistics, sys
cg = {}
for line in open(sys.argv[1]):
    name, t, instructions, rhs = line.split()
    cg.setdefault(name, []).append((float(t), int(instructions), int(rhs)))
walls, full = {}, {}
for line in open(sys.argv[2]):
    name, wall, rhs, steps, tfull = line.split()
    walls.setdefault(name, []).append(float(wall))
    full[name] = (int(rhs), int(steps), float(tfull))
def per_rhs(name):
    (_, i1, r1), (_, i2, r2) = sorted(cg[name])
    return (i2 - i1) / (r2 - r1)
def fmt(v, unit):
    return f"{v / 1e3:,.0f} k" if unit == "k" else (f"{v:,.0f}" if unit == "n" else f"{v:.3f}")
rows = [("Table 1 pendulum, n_a = 3 quasi-static, RK-Merson 1e-6, 20 s", "pendulum"),
        ("crane, 12 falls, n_a = 1, RK-Merson 1e-6, 36 s", "crane")]
print("| scene | instructions / rhs: plugin | floor | ratio | rhs / simulated s: plugin | floor | ratio "
      "| steps: plugin | floor | process wall [s]: plugin | floor | ratio |")
print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
for label, scene in rows:
    p, f = scene + "-plugin", scene + "-floor"
    ip, i_f = per_rhs(p), per_rhs(f)
    rp, rf = full[p][0] / full[p][2], full[f][0] / full[f][2]
    wp, wf = statistics.median(walls[p]), statistics.median(walls[f])
    print(f"| {label} | {fmt(ip, 'k')} | {fmt(i_f, 'k')} | {ip / i_f:.2f} | {rp:,.0f} | {rf:,.0f} | {rp / rf:.2f} "
          f"| {full[p][1]:,} | {full[f][1]:,} | {wp:.3f} | {wf:.3f} | {wp / wf:.2f} |")
print()
print("Instructions per rhs: callgrind, (I(T2) - I(T1)) / (rhs(T2) - rhs(T1)), T = 1 and 2 s (pendulum), "
      "1.5 and 3 s (crane), reports included.")
print(f"Process walls: taskset -c {sys.argv[4]}, interleaved, median of {sys.argv[3]}; "
      "rhs and steps of the full-length runs.")
print("The crane's floor is not the same physics: its separate springs hold the hook block's rotation "
      "stiffly (the reeved rope slides over the sheaves), so it takes more steps (bench/floor/floor_crane.cpp); "
      "compare the crane per rhs, not per simulated second.")
print("Raw callgrind runs (name, t-end [s], instructions, rhs):")
for name, runs in cg.items():
    for t, i, r in sorted(runs):
        print(f"    {name} {t:g} {i} {r}")
print("Raw process walls [s]:")
for name, w in walls.items():
    print(f"    {name} " + " ".join(f"{x:.3f}" for x in w))
PY
