#!/usr/bin/env bash
# Real-time factor of the default demo case (Table 1 pendulum, 20 s, one n_a per run) for a list of
# configurations: each is run REPEATS times (interleaved, so machine noise hits all alike) with
# reports every 0.01 s (the demo's default) and every 1 s (integration alone, nearly), and the
# medians printed as a Markdown table. One case at a time: one core.
#
# usage: bench/speed_table.sh [REPEATS] [BINARY]     (defaults 5, build/examples/reeving-pendulum)
# The configurations are the CONFIGS lines below: "label|reeving-pendulum options".
set -euo pipefail
n=${1:-5}
bin=${2:-build/examples/reeving-pendulum}
CONFIGS=(
    "n_a = 0, rk-merson 1e-6|--axial-modes 0 --integrator rk-merson --accuracy 1e-6"
    "n_a = 3 Dynamic, rk-merson 1e-6|--axial-modes 3 --axial-dynamics dynamic --integrator rk-merson --accuracy 1e-6"
    "n_a = 3 QuasiStatic, rk-merson 1e-6|--axial-modes 3 --axial-dynamics quasi-static --integrator rk-merson --accuracy 1e-6"
    "n_a = 3 QuasiStatic, rk-merson 1e-7|--axial-modes 3 --axial-dynamics quasi-static --integrator rk-merson --accuracy 1e-7"
    "n_a = 3 QuasiStatic, rk-merson 1e-8|--axial-modes 3 --axial-dynamics quasi-static --integrator rk-merson --accuracy 1e-8"
    "n_a = 3 QuasiStatic, cpodes 1e-7|--axial-modes 3 --axial-dynamics quasi-static --integrator cpodes --accuracy 1e-7"
)
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
for i in $(seq "$n"); do
    for c in "${!CONFIGS[@]}"; do
        IFS='|' read -r label opts <<<"${CONFIGS[$c]}"
        for ri in 0.01 1; do
            # shellcheck disable=SC2086
            "$bin" $opts --report-interval "$ri" --no-plots --quiet --out "$out/run" >/dev/null
            python3 - "$out/run/summary.json" "$c" "$ri" >>"$out/runs.txt" <<'EOF'
import json, sys
s = json.load(open(sys.argv[1]))
print(sys.argv[2], sys.argv[3], s["wall_seconds"], s["steps"], s["rhs_evaluations"], s["t_end"])
EOF
        done
    done
done
python3 - "$out/runs.txt" "${CONFIGS[@]}" <<'EOF'
import statistics, sys
rows = [l.split() for l in open(sys.argv[1])]
labels = [c.split("|")[0] for c in sys.argv[2:]]
print("| configuration | steps | rhs | wall, 1 s reports [s] | real-time factor | wall, 0.01 s reports [s] | real-time factor | per rhs, 1 s reports [us] |")
print("|---|---:|---:|---:|---:|---:|---:|---:|")
for c, label in enumerate(labels):
    def med(ri):
        return statistics.median(float(r[2]) for r in rows if int(r[0]) == c and r[1] == ri)
    one = [r for r in rows if int(r[0]) == c and r[1] == "1"][0]
    steps, rhs, tend = int(one[3]), int(one[4]), float(one[5])
    w1, w001 = med("1"), med("0.01")
    print(f"| {label} | {steps} | {rhs} | {w1:.3f} | {tend / w1:.0f}x | {w001:.3f} | {tend / w001:.0f}x | {1e6 * w1 / rhs:.1f} |")
EOF
