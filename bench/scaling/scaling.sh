#!/usr/bin/env bash
# Instructions per right-hand side (callgrind) of one rope zigzagging over N deviation sheaves
# (bench-scaling, see bench/scaling/main.cpp), as markdown tables:
#   (a) against N = 1, 2, 4, ..., 64 at n_a = 3, n_t = 1, with the figure per sheave (/ N) and its
#       ratio to N = 4's (expected constant within 20 % from 4 to 64);
#   (b) against n_a = 0, 1, 2, 4, 8 at n_t = 1 and n_t = 0, 1, 2, 4, 8 at n_a = 0, for N = 8.
# Each case runs bench-scaling under callgrind twice, with K and 2K evaluations (the same 2K states
# recorded from an RK-Merson 1e-6 run in both, set-up uninstrumented: --instr-atstart=no); the
# figure is (I(2K) - I(K)) / K, deterministic. Runs one process at a time (one core).
# Usage: bench/scaling/scaling.sh [BUILD_DIR]   (default build; needs BUILD_DIR/bench/bench-scaling)
# Environment: K (default 20) evaluations of the short run; SHEAVES (default "1 2 4 8 16 32 64").
set -euo pipefail
build=${1:-build}
exe=$build/bench/bench-scaling
[ -x "$exe" ] || { echo "scaling.sh: $exe not found (cmake --build $build --target bench-scaling)" >&2; exit 2; }
K=${K:-20}
sheaves=${SHEAVES:-"1 2 4 8 16 32 64"}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# count N NA NT EVALUATIONS: sets I (instructions) and M (modal coordinates)
count() {
    valgrind --tool=callgrind --callgrind-out-file=/dev/null --instr-atstart=no "$exe" --sheaves "$1" \
        --axial-modes "$2" --transverse-modes "$3" --evaluations "$4" --record $((2 * K)) \
        >"$tmp/out" 2>"$tmp/err" || { cat "$tmp/out" "$tmp/err" >&2; exit 1; }
    I=$(sed -n 's/.*Collected : \([0-9]*\).*/\1/p' "$tmp/err")
    M=$(sed -n 's/.*, \([0-9]*\) modal coordinates.*/\1/p' "$tmp/out")
    [ -n "$I" ] && [ -n "$M" ] || { echo "scaling.sh: no count in the output" >&2; cat "$tmp/out" "$tmp/err" >&2; exit 1; }
}
# per_rhs N NA NT: sets P (instructions per rhs) and M; logs both counts to stderr
per_rhs() {
    local a
    count "$1" "$2" "$3" "$K"
    a=$I
    count "$1" "$2" "$3" $((2 * K))
    P=$(((I - a) / K))
    echo "  N = $1, n_a = $2, n_t = $3: I($K) = $a, I($((2 * K))) = $I, $P per rhs (${SECONDS}s)" >&2
}

echo "Instructions per rhs of $exe (callgrind, (I(2K) - I(K)) / K with K = $K; RK-Merson 1e-6 states)"
echo
echo "(a) n_a = 3, n_t = 1 (QuasiStatic axial modes, VelocityModel::Complete)"
echo
echo "| N sheaves | spans | modal coordinates | instructions / rhs | / N | ratio to N = 4 |"
echo "|---|---|---|---|---|---|"
declare -A perN modal
for n in $sheaves; do
    per_rhs "$n" 3 1
    perN[$n]=$P modal[$n]=$M
done
ref=${perN[4]:-}
for n in $sheaves; do
    awk -v n="$n" -v i="${perN[$n]}" -v m="${modal[$n]}" -v ref="$ref" 'BEGIN {
        r = ref == "" ? "-" : sprintf("%.2f", (i / n) / (ref / 4));
        printf "| %d | %d | %d | %.0f | %.0f | %s |\n", n, n + 1, m, i, i / n, r }'
done

echo
echo "(b) N = 8 (9 spans)"
echo
echo "| n_a | n_t | modal coordinates | instructions / rhs | ratio to n_a = 0, n_t = 1 |"
echo "|---|---|---|---|---|"
declare -A perM modalM
cases="0,1 1,1 2,1 4,1 8,1 0,0 0,2 0,4 0,8"
for c in $cases; do
    per_rhs 8 "${c%,*}" "${c#*,}"
    perM[$c]=$P modalM[$c]=$M
done
for c in $cases; do
    awk -v na="${c%,*}" -v nt="${c#*,}" -v i="${perM[$c]}" -v m="${modalM[$c]}" -v ref="${perM[0,1]}" 'BEGIN {
        printf "| %d | %d | %d | %.0f | %.2f |\n", na, nt, m, i, i / ref }'
done
echo
echo "(script: ${SECONDS} s)"
