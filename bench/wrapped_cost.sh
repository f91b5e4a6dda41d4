#!/usr/bin/env bash
# Instructions per right-hand side with wrapped sheaves against point sheaves, for the paper's
# pendulum (reeving-pendulum --axial-modes 3, the demo's default case) and the 12-fall crane
# (reeving-crane --falls 12, n_a = 1 quasi-static): callgrind totals of two runs of different length
# (pendulum t-end 1 s and 2 s, crane 2 s and 4 s: rest, then the lift starting), so start-up,
# static equilibrium and output cancel, divided by the difference of their rhs counts (summary.json
# "rhs_evaluations"). Deterministic; about 4 minutes under callgrind.
#
# usage: bench/wrapped_cost.sh [BUILD_DIR]     (default build; the demos must be built)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
command -v valgrind >/dev/null || { echo "wrapped_cost.sh: valgrind not found" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
declare -A cost
run() {  # scene model t: one callgrind run
    local scene=$1 model=$2 t=$3
    case $scene in
        pendulum) set -- "$build/examples/reeving-pendulum" --axial-modes 3 ;;
        crane) set -- "$build/examples/reeving-crane" --falls 12 ;;
    esac
    valgrind --tool=callgrind --callgrind-out-file="$tmp/cg.$scene.$model.$t" "$@" --sheaves "$model" --no-plots \
        --quiet --t-end "$t" --out "$tmp/$scene-$model-$t" >/dev/null 2>&1
}
for scene in pendulum crane; do
    if [ "$scene" = pendulum ]; then short=1 long=2; else short=2 long=4; fi
    for model in point wrapped; do
        run "$scene" "$model" "$short"
        run "$scene" "$model" "$long"
        cost[$scene.$model]=$(python3 - "$tmp" "$scene" "$model" "$short" "$long" <<'PY'
import json, re, sys
tmp, scene, m, a, b = sys.argv[1:]
tot = lambda t: int(re.search(r'^summary: (\d+)', open(f'{tmp}/cg.{scene}.{m}.{t}').read(), re.M).group(1))
rhs = lambda t: json.load(open(f'{tmp}/{scene}-{m}-{t}/summary.json'))['rhs_evaluations']
print((tot(b) - tot(a)) / (rhs(b) - rhs(a)))
PY
)
    done
done
echo "| scene | sheave model | instructions / rhs | ratio to point |"
echo "|---|---|---:|---:|"
for scene in pendulum crane; do
    for model in point wrapped; do
        python3 -c "print('| $scene | $model | %d k | %.2f |' % (round(${cost[$scene.$model]} / 1000), ${cost[$scene.$model]} / ${cost[$scene.point]}))"
    done
done
