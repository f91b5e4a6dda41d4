#!/usr/bin/env bash
# Usage: bench/elevator/elevator_sweep.sh [BUILD_DIR] [TIMEOUT_S]
# Robustness sweep of the traction elevator: the stall and the emergency stop, each with
# one option changed from the demo's defaults (accuracy, roping, compensation, report interval,
# friction, mode counts, rope damping), then the stall at --friction 10 (e^(mu alpha) = 4.4e13, a
# stress case beyond real grooves) with the same changes. One Markdown row per run: exit status
# (124 = TIMEOUT_S, default 60 s, of wall reached), stick/slip transitions, real-time factor,
# relative energy residual, friction work, and the first line of any error.
set -uo pipefail
build="${1:-build}"
limit="${2:-60}"
exe="$build/examples/reeving-elevator"
[ -x "$exe" ] || { echo "elevator_sweep.sh: $exe not found (build the reeving-elevator target)" >&2; exit 2; }
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
variants=("" "--accuracy 1e-5" "--accuracy 1e-7" "--roping 2:1" "--compensation" "--report-interval 0.003"
          "--report-interval 0.001" "--transverse-modes 2" "--axial-modes 2" "--axial-modes 0"
          "--retardation-time 0.005")
printf '| scenario | friction | option | exit | transitions | real-time factor | energy residual | friction work [J] | error |\n'
printf '|---|---|---|---|---|---|---|---|---|\n'
row() {  # scenario friction option...
    local scenario=$1 mu=$2
    shift 2
    rm -rf "$tmp/out"
    # shellcheck disable=SC2068
    timeout "$limit" "$exe" --scenario "$scenario" --friction "$mu" $@ --out "$tmp/out" --no-plots --quiet \
        >/dev/null 2>"$tmp/err"
    local rc=$? fields="| | | |"
    if [ $rc = 0 ]; then
        fields=$(python3 -c "import json,sys; t=json.load(open(sys.argv[1]))['traction_table'][0]; print('| %d | %.2f | %.1e | %.1f |' % (t['stick_slip_transitions'], t['real_time_factor'], t['energy_residual_relative'], t['friction_work_J']))" "$tmp/out/summary.json")
    fi
    printf '| %s | %s | %s | %s %s %s |\n' "$scenario" "$mu" "${*:-defaults}" "$rc" "$fields" \
        "$(head -n 1 "$tmp/err" | cut -c1-150 | tr '|' '/')"
}
for scenario in stall emergency-stop; do
    for v in "${variants[@]}"; do row "$scenario" 0.2 $v; done
    row "$scenario" 0.1
    row "$scenario" 0.4
done
for v in "${variants[@]}"; do row stall 10 $v; done
