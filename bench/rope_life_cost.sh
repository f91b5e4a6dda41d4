#!/usr/bin/env bash
# RopeLifeMonitor's cost in the gantry crane's default cycle, deterministically: callgrind's
# instruction totals of one run with the monitor recording every report (0.02 s) and one without
# (bench-rope-life --once with|without: the same steps), and their relative difference. Then the
# walls of alternating pairs (bench-rope-life 9), whose median ratio moves with the machine's load.
# About 2 minutes.
#
# usage: bench/rope_life_cost.sh [BUILD_DIR]     (default build; bench-rope-life must be built)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
command -v valgrind >/dev/null || { echo "rope_life_cost.sh: valgrind not found" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
declare -A total
for which in without with; do
    valgrind --tool=callgrind --callgrind-out-file="$tmp/cg.$which" "$build/bench/bench-rope-life" --once "$which" \
        >"$tmp/$which.log" 2>&1
    total[$which]=$(callgrind_annotate "$tmp/cg.$which" 2>/dev/null | awk '/PROGRAM TOTALS/ {gsub(",", "", $1); print $1}')
    echo "$which: $(grep -E '^(with|without):' "$tmp/$which.log"), ${total[$which]} instructions"
done
awk -v a="${total[with]}" -v b="${total[without]}" \
    'BEGIN { printf "monitor: %.0f instructions, %+.2f %% of the run without it\n", a - b, 100 * (a - b) / b }'
"$build/bench/bench-rope-life" 9 | tail -1
