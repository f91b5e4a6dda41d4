#!/usr/bin/env bash
# Instructions per right-hand side of the paper's pendulum (reeving-pendulum --axial-modes 3, the
# demo's default case) with the point sheave and with the wrapped sheave (--sheaves wrapped), and
# their ratio: callgrind totals of two runs of different length (t-end 1 s and 2 s), so start-up,
# static equilibrium and output cancel, divided by the difference of their rhs counts
# (summary.json "rhs_evaluations"). Deterministic; about 1 minute under callgrind.
#
# usage: bench/wrapped_cost.sh [BUILD_DIR]     (default build; the demo must be built)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
command -v valgrind >/dev/null || { echo "wrapped_cost.sh: valgrind not found" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
declare -A cost
for model in point wrapped; do
    for t in 1 2; do
        valgrind --tool=callgrind --callgrind-out-file="$tmp/cg.$model.$t" \
            "$build/examples/reeving-pendulum" --axial-modes 3 --sheaves "$model" --no-plots --quiet \
            --t-end "$t" --out "$tmp/$model-$t" >/dev/null 2>&1
    done
    cost[$model]=$(python3 - "$tmp" "$model" <<'PY'
import json, re, sys
tmp, m = sys.argv[1], sys.argv[2]
tot = lambda f: int(re.search(r'^summary: (\d+)', open(f).read(), re.M).group(1))
rhs = lambda d: json.load(open(d + '/summary.json'))['rhs_evaluations']
print((tot(f'{tmp}/cg.{m}.2') - tot(f'{tmp}/cg.{m}.1')) / (rhs(f'{tmp}/{m}-2') - rhs(f'{tmp}/{m}-1')))
PY
)
done
echo "| sheave model | instructions / rhs | ratio to point |"
echo "|---|---:|---:|"
for model in point wrapped; do
    python3 -c "print('| $model | %d k | %.2f |' % (round(${cost[$model]} / 1000), ${cost[$model]} / ${cost[point]}))"
done
