#!/usr/bin/env bash
# Checks that a speed-up changes no result: runs the pendulum and crane demos of two
# builds at accuracy 1e-10 (environment ACCURACY overrides it) and compares their timeseries.csv
# column by column:
#   reeving-pendulum --axial-modes 3 --accuracy 1e-10             (20 s, reports every 0.01 s)
#   reeving-crane --falls 12 --axial-modes 1 --accuracy 1e-10     (36 s, reports every 0.02 s)
# For every column it prints the largest difference relative to the baseline column's largest
# absolute value (the absolute difference for an all-zero column). It fails (exit status 1) if a
# payload-path or force column differs by more than TOL = 1e-8 relative, or if the two files
# differ in columns, rows or report times:
#   pendulum: x, y, theta, axial_force_payload, axial_force_sheave;
#   crane:    trolley_x, hook_x, hook_height, sway, payload_angle, fall_1..fall_n, motor_torque,
#             trolley_force.
# The other columns (energy, constraint error, energy residual, powers, ...) are printed, not
# checked: at 1e-10 some are round-off (e.g. the constraint error, ~1e-9 N).
# Takes about 1 minute of CPU per build (the crane at 1e-10: ~40 s of it, on the current main).
#
# usage: bench/compare_timeseries.sh BASELINE_BIN_DIR NEW_BIN_DIR
#   each dir holds reeving-pendulum and reeving-crane (e.g. /work/baseline, build/examples);
#   environment: TOL (default 1e-8); ACCURACY (default 1e-10: the integrator's accuracy of all four
#   runs; the crane's forces at 1e-10 carry the integration error, 2.8e-6 between its own 1e-10 and
#   1e-11 runs, so a changed step sequence moves them by ~1e-7: compare at 1e-12 to see the change
#   itself); OUT=DIR keeps the four runs' outputs in DIR.
# Exit status: 0 all checked columns agree; 1 they do not (or a run failed); 2 bad command line.
set -euo pipefail
if [ $# -ne 2 ]; then
    sed -n '/^# usage:/,/^# Exit status:/p' "$0" | sed 's/^# \{0,1\}//' >&2
    exit 2
fi
base=$1
new=$2
tol=${TOL:-1e-8}
accuracy=${ACCURACY:-1e-10}
for dir in "$base" "$new"; do
    for program in reeving-pendulum reeving-crane; do
        [ -x "$dir/$program" ] || { echo "compare_timeseries.sh: $dir/$program not found or not executable" >&2; exit 2; }
    done
done
if [ -n "${OUT:-}" ]; then
    out=$OUT
    mkdir -p "$out"
else
    out=$(mktemp -d)
    trap 'rm -rf "$out"' EXIT
fi

run() {  # label dir program options...
    local label=$1 dir=$2 program=$3
    shift 3
    if ! "$dir/$program" "$@" --no-plots --quiet --out "$out/$label" >"$out/$label.log" 2>&1; then
        echo "compare_timeseries.sh: $dir/$program $* failed:" >&2
        cat "$out/$label.log" >&2
        exit 1
    fi
}
run pendulum-base "$base" reeving-pendulum --axial-modes 3 --accuracy "$accuracy"
run pendulum-new "$new" reeving-pendulum --axial-modes 3 --accuracy "$accuracy"
run crane-base "$base" reeving-crane --falls 12 --axial-modes 1 --accuracy "$accuracy"
run crane-new "$new" reeving-crane --falls 12 --axial-modes 1 --accuracy "$accuracy"

python3 - "$out" "$tol" "$base" "$new" <<'PY'
import csv, json, re, sys
out, tol, base, new = sys.argv[1], float(sys.argv[2]), sys.argv[3], sys.argv[4]
CHECKED = {
    "pendulum": lambda c: c in ("x", "y", "theta", "axial_force_payload", "axial_force_sheave"),
    "crane": lambda c: c in ("trolley_x", "hook_x", "hook_height", "sway", "payload_angle", "motor_torque",
                             "trolley_force") or re.fullmatch(r"fall_\d+", c) is not None,
}
def load(path):
    with open(path) as f:
        rows = list(csv.reader(f))
    return rows[0], [[float(x) for x in r] for r in rows[1:]]
ok = True
print(f"baseline {base}, new {new}; checked columns (*) must agree to {tol:g} relative")
for scene in ("pendulum", "crane"):
    hb, rb = load(f"{out}/{scene}-base/timeseries.csv")
    hn, rn = load(f"{out}/{scene}-new/timeseries.csv")
    sb = json.load(open(f"{out}/{scene}-base/summary.json"))
    sn = json.load(open(f"{out}/{scene}-new/summary.json"))
    print(f"\n{scene}: {len(rb)} reports; steps {sb['steps']} -> {sn['steps']}, "
          f"rhs {sb['rhs_evaluations']} -> {sn['rhs_evaluations']}")
    if hb != hn or len(rb) != len(rn):
        print(f"  FAIL: columns or row counts differ ({len(hb)} x {len(rb)} vs {len(hn)} x {len(rn)})")
        ok = False
        continue
    print(f"  {'column':24s} {'max |base|':>14s} {'max |diff|':>14s} {'relative':>10s}")
    for j, name in enumerate(hb):
        scale = max(abs(r[j]) for r in rb)
        diff = max(abs(a[j] - b[j]) for a, b in zip(rb, rn))
        rel = diff / scale if scale > 0 else diff
        checked = name == "t" or CHECKED[scene](name)
        bad = checked and (rel > tol if name != "t" else diff != 0)
        ok = ok and not bad
        print(f"  {name + (' *' if checked else ''):24s} {scale:14.6g} {diff:14.6g} {rel:10.3g}{'  FAIL' if bad else ''}")
print("\n" + ("PASS: the checked columns agree" if ok else "FAIL: see the columns marked FAIL"))
sys.exit(0 if ok else 1)
PY
