#!/usr/bin/env bash
# Instructions per right-hand side of the default pendulum demo (Table 1 pendulum, 1 m/s push,
# quasi-static n_a = 3, n_t = 1, RK-Merson 1e-6), counted by callgrind from two runs of different
# length: (I(T2) - I(T1)) / (rhs(T2) - rhs(T1)), so start-up and set-up cancel (summary.json has
# "rhs_evaluations"). Also prints the inclusive per-rhs counts of the span kernels
# (SpanModel<2>::evaluate, AxialCondensation<2>::evaluate and ::evaluateRates). Deterministic.
# Usage: bench/moving_string/rhs_cost.sh [path/to/reeving-pendulum] [T1] [T2]
#        (defaults: build/examples/reeving-pendulum, 2 and 4 [s])
set -euo pipefail
exe=${1:-build/examples/reeving-pendulum}
t1=${2:-2}
t2=${3:-4}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
run() {  # tend -> "instructions rhs" and per-function inclusive counts in $work/fn.$1
    valgrind --tool=callgrind --callgrind-out-file="$work/cg.$1" "$exe" --axial-modes 3 --t-end "$1" \
        --no-plots --quiet --out "$work/out.$1" >/dev/null 2>"$work/log.$1"
    local instr rhs
    instr=$(sed -n 's/.*Collected : \([0-9]*\).*/\1/p' "$work/log.$1")
    rhs=$(sed -n 's/.*"rhs_evaluations": *\([0-9]*\).*/\1/p' "$work/out.$1/summary.json")
    callgrind_annotate --inclusive=yes "$work/cg.$1" 2>/dev/null | tr -d ',' >"$work/fn.$1"
    echo "$instr $rhs"
}
fn() {  # file pattern -> inclusive count of the first matching line
    grep -F -- "$2" "$1" | head -1 | awk '{print $1}'
}
read -r i1 r1 < <(run "$t1")
read -r i2 r2 < <(run "$t2")
awk -v i1="$i1" -v i2="$i2" -v r1="$r1" -v r2="$r2" 'BEGIN {
    printf "rhs evaluations %d -> %d; instructions per rhs: %.0f\n", r1, r2, (i2 - i1) / (r2 - r1) }'
for f in "SpanModel<2>::evaluate(" "AxialCondensation<2>::evaluate(" "AxialCondensation<2>::evaluateRates("; do
    a=$(fn "$work/fn.$t1" "$f"); b=$(fn "$work/fn.$t2" "$f")
    awk -v a="${a:-0}" -v b="${b:-0}" -v r1="$r1" -v r2="$r2" -v f="$f" 'BEGIN {
        printf "  %-40s %.0f per rhs (inclusive)\n", f, (b - a) / (r2 - r1) }'
done
