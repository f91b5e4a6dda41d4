#!/usr/bin/env bash
# Quasi-static transverse modes on the Table 1 pendulum: the demo's
# default case (reeving-pendulum --axial-modes 3: quasi-static axial modes, n_t = 1, RK-Merson, 20 s,
# reports every 0.01 s) with the 3 m span's transverse modes as states (none) and condensed
# (horizontal), at accuracy 1e-6 (the default) and 1e-10. Prints per accuracy: steps, rhs, process
# wall (summary.json wall_seconds: the run without start-up; pinned to CORE, median of REPEATS), and the largest difference of the condensed
# run from the dynamic one over the run: payload path |(x, y)| [m], payload-end axial force [N]
# (absolute and relative to its largest value).
# usage: bench/quasi_static_transverse/compare.sh [BUILD_DIR]   (environment: REPEATS=5, CORE=1)
set -euo pipefail
cd "$(dirname "$0")/../.."
build=${1:-build}
repeats=${REPEATS:-5}
core=${CORE:-1}
cmake --build "$build" -j2 --target reeving-pendulum >/dev/null
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for acc in 1e-6 1e-10; do
    for q in none horizontal; do
        for r in $(seq "$repeats"); do
            taskset -c "$core" "$build/examples/reeving-pendulum" --axial-modes 3 --quasi-static-transverse "$q" \
                --accuracy "$acc" --no-plots --quiet --out "$tmp/$acc-$q-$r" >/dev/null
        done
    done
done
python3 - "$tmp" "$repeats" <<'PY'
import csv, json, statistics, sys, math
tmp, repeats = sys.argv[1], int(sys.argv[2])
def load(acc, q, r=1):
    d = f"{tmp}/{acc}-{q}-{r}"
    rows = list(csv.DictReader(open(d + "/timeseries.csv")))
    return json.load(open(d + "/summary.json")), rows
print("| accuracy | transverse modes of the 3 m span | steps | rhs | wall [s] (median of %d) | payload path diff [m] | payload-end force diff [N] (relative) |" % repeats)
print("|---|---|---:|---:|---:|---:|---:|")
for acc in ("1e-6", "1e-10"):
    _, ref = load(acc, "none")
    for q in ("none", "horizontal"):
        js, rows = load(acc, q)
        wall = statistics.median(json.load(open(f"{tmp}/{acc}-{q}-{r}/summary.json"))["wall_seconds"] for r in range(1, repeats + 1))
        if q == "none":
            diff = "-"
            fd = "-"
        else:
            assert len(rows) == len(ref)
            dp = max(math.hypot(float(a["x"]) - float(b["x"]), float(a["y"]) - float(b["y"])) for a, b in zip(rows, ref))
            df = max(abs(float(a["axial_force_payload"]) - float(b["axial_force_payload"])) for a, b in zip(rows, ref))
            fmax = max(abs(float(b["axial_force_payload"])) for b in ref)
            diff = "%.2e" % dp
            fd = "%.3g (%.1e)" % (df, df / fmax)
        print(f"| {acc} | {'states (dynamic)' if q == 'none' else 'condensed'} | {js['steps']} | {js['rhs_evaluations']} | {wall:.3f} | {diff} | {fd} |")
PY
