#!/usr/bin/env bash
# A/B timing of two reeving-pendulum binaries in one run: the runs alternate (A, B, A, B, ...) so
# machine noise hits both alike; prints every run and the medians and their ratio.
#
# usage: bench/perf_ab.sh BINARY_A BINARY_B [REPEATS] [-- demo options]
# default demo options: --axial-modes 3 --t-end 5 (one case, RK-Merson 1e-6, the Table 1 pendulum)
# B_EXTRA="..." adds options to B's runs only (e.g. --axial-dynamics dynamic, which older builds lack).
set -euo pipefail
a=$1 b=$2 n=${3:-5}
shift 2; [ $# -gt 0 ] && shift
[ "${1:-}" = "--" ] && shift
opts=("$@")
[ ${#opts[@]} -eq 0 ] && opts=(--axial-modes 3 --t-end 5)
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
for i in $(seq "$n"); do
    for who in A B; do
        bin=$a extra=()
        [ $who = B ] && bin=$b && read -r -a extra <<<"${B_EXTRA:-}"
        "$bin" "${opts[@]}" "${extra[@]}" --no-plots --quiet --out "$out/$who" >/dev/null
        python3 - "$out/$who" "$who" "$i" >>"$out/runs.txt" <<'EOF'
import json, pathlib, sys
d = pathlib.Path(sys.argv[1])
summary = next(d.rglob("summary.json")) if not (d / "summary.json").exists() else d / "summary.json"
s = json.loads(summary.read_text())
print(sys.argv[2], sys.argv[3], s["wall_seconds"], s["steps"], s["rhs_evaluations"])
EOF
    done
done
cat "$out/runs.txt"
python3 - "$out/runs.txt" <<'EOF'
import statistics, sys
rows = [l.split() for l in open(sys.argv[1])]
med = {w: statistics.median(float(r[2]) for r in rows if r[0] == w) for w in "AB"}
rhs = {w: [int(r[4]) for r in rows if r[0] == w][0] for w in "AB"}
print(f"median wall A {med['A']:.3f} s ({rhs['A']} rhs), B {med['B']:.3f} s ({rhs['B']} rhs); "
      f"A/B = {med['A'] / med['B']:.2f}; per rhs A/B = {(med['A'] / rhs['A']) / (med['B'] / rhs['B']):.2f}")
EOF
