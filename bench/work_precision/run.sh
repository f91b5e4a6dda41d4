#!/usr/bin/env bash
# Reproduces the work-precision study of docs/performance.md: bench-work-precision on the paper's
# pendulum, n_a = 3 in one process and n_a = 0, 1 in another (one process per core of the 2-core
# machine: timings want one run per idle core), then the two merged into one table and one plot per
# n_a. Resumable: each part keeps the points already in its results.csv (--resume) and its cached
# references. About 50 minutes on 2 cores.
# Usage: bench/work_precision/run.sh [out-dir]   (default out/work-precision; needs ./scripts/build.sh)
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
B=$root/build/bench/bench-work-precision
out=${1:-$root/out/work-precision}
[[ -x $B ]] || { echo "run ./scripts/build.sh first ($B missing)" >&2; exit 1; }
# Cap: a run past 60 s of wall is "too slow" (also stopped early once its projected wall exceeds
# 1.25 x 60 s), the tighter settings are measured all the same (--no-cap-skip); every successful
# point is timed 3 times and the median recorded.
common=(--cap 60 --project-cap 1.25 --no-cap-skip --repeats 3 --repeat-below 61 --resume)
mkdir -p "$out/na3" "$out/na01" "$out/all"
"$B" --axial-modes 3 "${common[@]}" --no-plots --out "$out/na3" > "$out/na3.log" 2>&1 &
"$B" --axial-modes 0,1 "${common[@]}" --no-plots --out "$out/na01" > "$out/na01.log" 2>&1 &
wait
cp "$out/na3/reference_na3.csv" "$out/na01/reference_na0.csv" "$out/na01/reference_na1.csv" "$out/all/"
{ cat "$out/na3/results.csv"; tail -n +2 "$out/na01/results.csv"; } > "$out/all/results.csv"
"$B" --axial-modes 0,1,3 "${common[@]}" --out "$out/all"   # every point recorded: tables and plots only
echo "tables: $out/all/table.md, $out/all/reference_check.txt; plots: $out/all/work_precision_na*.png"
