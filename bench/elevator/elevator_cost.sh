#!/usr/bin/env bash
# Usage: bench/elevator/elevator_cost.sh [BUILD_DIR] [REPEATS]
# The traction elevator's cost: for each scenario of reeving-elevator, pinned to one core
# (taskset -c 0), the real-time factor (simulated / wall, median of REPEATS runs, default 5) with the
# steps and right-hand sides: 1:1 with the default (wrapped) sheaves; then the cost of the friction
# events, 1:1 with point sheaves at mu 0.2 and again with --friction 10 (the sheave slips only in
# the stall, where the counterweight's fall is slack: no other stick/slip events; point sheaves, as
# with wrapped ones the slack fall's quasi-static amplitude stalls the Newton, see
# docs/elevator.md), steps, rhs and wall side by side; then each scenario roped 2:1 and each 1:1
# with the compensating rope (mu 0.2).
set -euo pipefail
build="${1:-build}"
repeats="${2:-5}"
exe="$build/examples/reeving-elevator"
[ -x "$exe" ] || { echo "elevator_cost.sh: $exe not found (build the reeving-elevator target)" >&2; exit 2; }
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
field() { python3 -c "import json,sys; t=json.load(open(sys.argv[1]))['traction_table'][0]; print(t[sys.argv[2]])" "$1" "$2"; }
printf '| roping | scenario | mu | traction | transitions | steps | rhs | wall [s] (median of %s) | real-time factor |\n' "$repeats"
printf '|---|---|---|---|---|---|---|---|---|\n'
for roping in 1:1 "1:1 point" 2:1 1:1+compensation; do
    for scenario in trip loading emergency-stop stall; do
        for mu in 0.2 10; do
            [ "$roping" != "1:1 point" ] && [ "$mu" = 10 ] && continue
            extra=(--roping "${roping%%[+ ]*}")
            [ "$roping" = 1:1+compensation ] && extra+=(--compensation)
            [ "$roping" = "1:1 point" ] && extra+=(--sheaves point)
            out="$tmp/${roping//[:+ ]/-}-$scenario-$mu"
            walls=()
            for ((i = 0; i < repeats; i++)); do
                taskset -c 0 "$exe" "${extra[@]}" --scenario "$scenario" --friction "$mu" --no-plots --quiet \
                    --out "$out" >/dev/null
                walls+=("$(field "$out/summary.json" wall_s)")
            done
            median="$(printf '%s\n' "${walls[@]}" | sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}')"
            s="$out/summary.json"
            simulated="$(field "$s" simulated_s)"
            printf '| %s | %s | %s | %s | %s | %s | %s | %.3f | %.2f |\n' "$roping" "$scenario" "$mu" "$(field "$s" traction)" \
                "$(field "$s" stick_slip_transitions)" "$(field "$s" steps)" "$(field "$s" rhs_evaluations)" "$median" \
                "$(python3 -c "print($simulated / $median)")"
        done
    done
done
