#!/usr/bin/env bash
# The demos' --visualize under a virtual X server (Debian's xvfb, mesa's software OpenGL):
#   1. reeving-crane --visualize: the window opens; a screenshot of it shows the machine (payload,
#      rope, hook block, trolley, steel parts: pixel counts by hue class); the run ends with exit 0
#      and complete outputs; the visualizer process has ended when the demo has.
#   2. reeving-pendulum --visualize: the same for the pendulum (payload, rope, sheave).
#   3. reeving-crane --visualize, window closed midway (WM_DELETE_WINDOW, as a close button): the
#      run goes on without it (message on stderr), ends with exit 0 and complete outputs; no
#      visualizer process is left.
#   4. reeving-crane --visualize with the visualizer process stopped (SIGSTOP: it reads no more
#      frames, as a hung window): the demo's watchdog ends it after 10 s of a blocked frame and the
#      run completes with exit 0 and complete outputs.
# Screenshots are kept in WORKDIR (crane.png, pendulum.png) for a human to look at.
# usage: test_visualizer.sh REEVING_CRANE REEVING_PENDULUM X11_WINDOW_TOOL WORKDIR
set -u
crane=$1 pendulum=$2 tool=$3 work=$4
fail() { echo "test_visualizer: FAIL: $*" >&2; exit 1; }
command -v Xvfb > /dev/null ||
  fail "Xvfb is not installed; the Visualizer tests need Debian's xvfb (./scripts/install-deps.sh installs it)"
rm -rf "$work" && mkdir -p "$work" || fail "cannot create $work"

# A private X server on a free display number (-displayfd: Xvfb picks it and writes it).
exec 3> "$work/display"
Xvfb -displayfd 3 -screen 0 1024x768x24 -nolisten tcp > "$work/xvfb.log" 2>&1 &
xvfb=$!
exec 3>&-
trap 'kill $xvfb 2> /dev/null; wait $xvfb 2> /dev/null' EXIT
for _ in $(seq 100); do [ -s "$work/display" ] && break; sleep 0.1; done
[ -s "$work/display" ] || fail "Xvfb did not start: $(cat "$work/xvfb.log")"
export DISPLAY=:$(head -1 "$work/display")
export LIBGL_ALWAYS_SOFTWARE=1
echo "test_visualizer: Xvfb on $DISPLAY"

# The simbody-visualizer child of process $1, if any.
viz_child() { ps -o pid= -o comm= --ppid "$1" 2> /dev/null | awk '$2 ~ /^simbody-visuali/ {print $1}'; }

# check_shot PNG_LINE NAME MIN_GREEN MIN_PURPLE MIN_YELLOW MIN_BLUE MIN_GREY
check_shot() {
  local line=$1 name=$2
  echo "test_visualizer: $name screenshot: $line"
  set -- $line
  # pixels W H background R G B non_background N colours C green G purple P yellow Y blue B grey S
  local colours=${11} green=${13} purple=${15} yellow=${17} blue=${19} grey=${21}
  [ "$colours" -ge "$min_colours" ] || fail "$name: $colours distinct colours < $min_colours (blank window?)"
  [ "$green" -ge "$min_green" ] || fail "$name: payload not visible ($green green pixels < $min_green)"
  [ "$purple" -ge "$min_purple" ] || fail "$name: rope not visible ($purple purple pixels < $min_purple)"
  [ "$yellow" -ge "$min_yellow" ] || fail "$name: hook block not visible ($yellow yellow pixels < $min_yellow)"
  [ "$blue" -ge "$min_blue" ] || fail "$name: trolley not visible ($blue blue pixels < $min_blue)"
  [ "$grey" -ge "$min_grey" ] || fail "$name: steel parts not visible ($grey grey pixels < $min_grey)"
}

# run_demo NAME WINDOW_TITLE ACTION EXE ARGS...: runs the demo in the background, waits for its
# window; ACTION "shot" takes a screenshot after 3 s, "close" closes the window after 2 s, "stop"
# stops the visualizer process (SIGSTOP) after 2 s, "none" only waits. Sets demo_rc, viz_pid.
run_demo() {
  local name=$1 title=$2 action=$3
  shift 3
  "$@" > "$work/$name.out" 2> "$work/$name.err" &
  local demo=$!
  "$tool" wait-window "$title" 60 || { kill $demo; fail "$name: no Visualizer window: $(cat "$work/$name.err")"; }
  viz_pid=$(viz_child $demo)
  [ -n "$viz_pid" ] || fail "$name: no simbody-visualizer child process found"
  case $action in
    shot) sleep 3; shot=$("$tool" screenshot "$work/$name.png" "$title") || fail "$name: screenshot failed" ;;
    close) sleep 2; "$tool" close-window "$title" || fail "$name: could not close the window" ;;
    stop) sleep 2; kill -STOP "$viz_pid" || fail "$name: could not stop the visualizer" ;;
  esac
  wait $demo
  demo_rc=$?
  [ "$demo_rc" -eq 0 ] || fail "$name: exit status $demo_rc: $(tail -5 "$work/$name.err")"
  # The visualizer ends with the demo (close() waits for it; the demo's exit reaped it).
  if kill -0 "$viz_pid" 2> /dev/null; then fail "$name: simbody-visualizer (pid $viz_pid) outlived the demo"; fi
}

# 1. The crane, shown. Thresholds: ~1/10 of the pixels measured at 3 s of the default cycle
#    (measured: see the comment lines below, 800x600 window).
run_demo crane reeving-crane shot "$crane" --visualize --t-end 6 --no-plots --quiet --out "$work/crane-out"
[ -s "$work/crane-out/summary.json" ] || fail "crane: summary.json missing"
# measured: colours 20 green 4305 purple 1046 yellow 201 blue 5437 grey 3024
min_colours=8 min_green=400 min_purple=100 min_yellow=20 min_blue=500 min_grey=300
check_shot "$shot" crane

# 2. The pendulum, shown (no hook block, no trolley).
run_demo pendulum reeving-pendulum shot "$pendulum" --visualize --axial-modes 1 --t-end 4 --no-plots --quiet --out "$work/pendulum-out"
[ -s "$work/pendulum-out/summary.json" ] || fail "pendulum: summary.json missing"
# measured: colours 9 green 214 purple 1580 grey 95
min_colours=4 min_green=20 min_purple=150 min_yellow=0 min_blue=0 min_grey=9
check_shot "$shot" pendulum

# 3. The crane, window closed midway.
run_demo crane-closed reeving-crane close "$crane" --visualize --t-end 6 --no-plots --quiet --out "$work/crane-closed-out"
grep -q "the Visualizer window was closed at t = " "$work/crane-closed.err" ||
  fail "crane-closed: no 'window was closed' message: $(cat "$work/crane-closed.err")"
[ -s "$work/crane-closed-out/summary.json" ] || fail "crane-closed: summary.json missing"
[ -s "$work/crane-closed-out/timeseries.csv" ] || fail "crane-closed: timeseries.csv missing"
rows=$(($(wc -l < "$work/crane-closed-out/timeseries.csv") - 1))
[ "$rows" -eq 301 ] || fail "crane-closed: $rows report rows, expected 301 (6 s every 0.02 s, and t = 0)"

# 4. The crane, visualizer hung.
run_demo crane-hung reeving-crane stop "$crane" --visualize --t-end 6 --no-plots --quiet --out "$work/crane-hung-out"
grep -q "the Visualizer read no frame for 10 s and was ended at t = .* s; the run goes on without it" "$work/crane-hung.err" ||
  fail "crane-hung: the run did not go on without the hung visualizer: $(cat "$work/crane-hung.err")"
[ -s "$work/crane-hung-out/summary.json" ] || fail "crane-hung: summary.json missing"

echo "test_visualizer: all four Visualizer runs behaved"
