#!/usr/bin/env bash
# Cost of the boom crane demo (reeving-boom-crane, its defaults: n_a = 1 quasi-static, n_t = 1,
# RK-Merson 1e-6, reports every 0.05 s) with point and with wrapped sheaves, as one Markdown table:
#   instructions per rhs: callgrind totals of two runs of different length, t-end 12 s and 14 s
#     (the load lifted, the crane slewing and luffing: the spatial ropes at fleet angles), so
#     start-up, static equilibrium and output cancel, divided by the difference of their rhs counts
#     (summary.json "rhs_evaluations"); deterministic;
#   steps, rhs and the energy residual (max |E - E0 - W| / max |W|) of the whole 40 s cycle, run
#     natively; deterministic.
# A sheave model whose run fails gets a row saying so (its message on stderr), and the script goes on.
# Builds reeving-boom-crane in BUILD_DIR first (-j2). About 3 minutes (most of it under callgrind).
#
# usage: bench/boom_crane_cost.sh [BUILD_DIR]     (default build)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
command -v valgrind >/dev/null || { echo "boom_crane_cost.sh: valgrind not found" >&2; exit 1; }
[ -f "$build/CMakeCache.txt" ] || cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" -j2 --target reeving-boom-crane >/dev/null
exe="$build/examples/reeving-boom-crane"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
short=12
long=14
echo "| sheave model | instructions / rhs | ratio to point | steps, 40 s cycle | rhs, 40 s cycle | energy residual / motion work |"
echo "|---|---:|---:|---:|---:|---:|"
point=
for model in point wrapped; do
    if ! "$exe" --sheaves "$model" --no-plots --quiet --out "$tmp/$model-full" >"$tmp/$model.log" 2>&1; then
        echo "boom_crane_cost.sh: --sheaves $model failed:" >&2
        cat "$tmp/$model.log" >&2
        echo "| $model | does not run (see the script's stderr) | | | | |"
        continue
    fi
    for t in $short $long; do
        valgrind --tool=callgrind --callgrind-out-file="$tmp/cg.$model.$t" "$exe" --sheaves "$model" --no-plots --quiet \
            --t-end "$t" --out "$tmp/$model-$t" >/dev/null 2>&1
    done
    row=$(python3 - "$tmp" "$model" "$short" "$long" "${point:-0}" <<'PY'
import json, re, sys
tmp, m, a, b, point = sys.argv[1:]
tot = lambda t: int(re.search(r'^summary: (\d+)', open(f'{tmp}/cg.{m}.{t}').read(), re.M).group(1))
rhs = lambda t: json.load(open(f'{tmp}/{m}-{t}/summary.json'))['rhs_evaluations']
cost = (tot(b) - tot(a)) / (rhs(b) - rhs(a))
full = json.load(open(f'{tmp}/{m}-full/summary.json'))
ratio = cost / float(point) if float(point) > 0 else 1.0
print(f"{cost:.0f}#| {m} | {round(cost / 1000)} k | {ratio:.2f} | {full['steps']:,} | {full['rhs_evaluations']:,} | "
      f"{full['energy_residual_relative']:.1e} |")
PY
)
    [ "$model" = point ] && point=${row%%#*}
    echo "${row#*#}"
done
