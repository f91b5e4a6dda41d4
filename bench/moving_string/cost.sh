#!/usr/bin/env bash
# Instructions per span evaluation (SpanModel<2>::evaluate, Table 1 rope, 20 m span in motion) of
# VelocityModel::Complete against ::Simplified, n_a = 0..3, n_t = 1..3, counted by callgrind: each
# case runs K and 2K evaluations and the difference / K is the per-evaluation count (set-up and
# start-up cancel). Deterministic (no wall clock).
# Usage: bench/moving_string/cost.sh [path/to/bench-moving-string]   (default build/bench/bench-moving-string)
set -euo pipefail
exe=${1:-build/bench/bench-moving-string}
K=2000
count() {  # nt na complete evaluations -> instructions
    valgrind --tool=callgrind --callgrind-out-file=/dev/null "$exe" --evaluate "$1" "$2" "$3" "$4" 2>&1 >/dev/null |
        sed -n 's/.*Collected : \([0-9]*\).*/\1/p'
}
echo "| n_a | n_t | Simplified [instr/eval] | Complete [instr/eval] | Complete / Simplified |"
echo "|---|---|---|---|---|"
for na in 0 1 2 3; do
    for nt in 1 2 3; do
        s1=$(count "$nt" "$na" 0 "$K"); s2=$(count "$nt" "$na" 0 $((2 * K)))
        c1=$(count "$nt" "$na" 1 "$K"); c2=$(count "$nt" "$na" 1 $((2 * K)))
        awk -v na="$na" -v nt="$nt" -v s1="$s1" -v s2="$s2" -v c1="$c1" -v c2="$c2" -v k="$K" 'BEGIN {
            s = (s2 - s1) / k; c = (c2 - c1) / k;
            printf "| %d | %d | %.0f | %.0f | %.3f |\n", na, nt, s, c, c / s }'
    done
done
