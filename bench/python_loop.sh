#!/usr/bin/env bash
# What a Python loop over the bindings costs against the C++ demo (issue 43, acceptance 4): the
# pendulum case stepped from Python with a report every --report-interval (Simulation.step_to, then
# the demo's row through observe_row), against reeving-pendulum running the same case, in the same
# run of this script. Both walls are the demos' own measure: from the stepper's first report to the
# last (scene building and static equilibrium excluded); the steps of the two must be equal (the
# same integration). Each repeat runs both, the order alternating; the table gives the medians, with
# the smallest and largest value, and the ratio Python / C++ (median of the per-repeat ratios).
#
# usage: bench/python_loop.sh [--repeats N] [--axial-modes N] [--t-end T] [--report-interval DT]
#                             [--build DIR] [--no-build]
#   defaults: 7 repeats, n_a = 1, the demo's 20 s and 0.01 s; build/ (its simbody_reeving and
#   reeving-pendulum targets built first unless --no-build).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=$root/build
repeats=7 modes=1 tend=20 interval=0.01 buildFirst=1
while [[ $# -gt 0 ]]; do
    case $1 in
        --repeats) repeats=$2; shift ;;
        --axial-modes) modes=$2; shift ;;
        --t-end) tend=$2; shift ;;
        --report-interval) interval=$2; shift ;;
        --build) build=$(cd "$2" && pwd); shift ;;
        --no-build) buildFirst=0 ;;
        -h|--help) sed -n '2,14p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
        *) echo "python_loop.sh: unknown option $1 (see --help)" >&2; exit 2 ;;
    esac
    shift
done
if [[ $buildFirst == 1 ]]; then
    cmake --build "$build" --target simbody_reeving reeving-pendulum > /dev/null
fi
python=$(sed -n 's/^Python3_EXECUTABLE:[A-Z]*=//p' "$build/CMakeCache.txt")
python=${python:-python3}
PYTHONPATH=$build/python exec "$python" - "$build" "$repeats" "$modes" "$tend" "$interval" <<'PY'
import json, os, platform, statistics, subprocess, sys, tempfile, time
import simbody_reeving as sr

build, repeats, modes, tend, interval = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), float(sys.argv[4]), float(sys.argv[5])
demo = os.path.join(build, "examples", "reeving-pendulum")


def cpp():
    with tempfile.TemporaryDirectory() as tmp:
        subprocess.run([demo, "--axial-modes", str(modes), "--t-end", repr(tend), "--report-interval", repr(interval),
                        "--out", tmp, "--no-plots", "--quiet"], check=True, stdout=subprocess.DEVNULL)
        s = json.load(open(os.path.join(tmp, "summary.json")))
    return s["wall_seconds"], s["steps"]


def python():
    scene = sr.PendulumScene(spans=sr.SpanOptions(axial_modes=modes))
    sim = scene.simulation(scene.make_initial_state(vx=1.0), integrator="rk-merson", accuracy=1e-6)
    reports = int(tend / interval + 1e-9)
    start = time.perf_counter()
    rows = [sim.observe_row()]
    for n in range(1, reports + 1):
        sim.step_to(n * interval)
        rows.append(sim.observe_row())
    return time.perf_counter() - start, sim.steps


walls = {"C++": [], "Python": []}
ratios = []
for k in range(repeats):
    order = [("C++", cpp), ("Python", python)]
    if k % 2:
        order.reverse()
    got = {}
    for name, f in order:
        got[name] = f()
        walls[name].append(got[name][0])
    assert got["C++"][1] == got["Python"][1], "different steps: %s" % got
    ratios.append(got["Python"][0] / got["C++"][0])

def cell(v, scale=1000):
    return "%.1f (%.1f to %.1f)" % (statistics.median(v) * scale, min(v) * scale, max(v) * scale)

print("python_loop.sh: %s, %d cpu, load %s; n_a = %d, %g s, a report every %g s (%d reports), %d steps, %d repeats"
      % (platform.processor() or platform.machine(), os.cpu_count(), " ".join("%.1f" % l for l in os.getloadavg()),
         modes, tend, interval, int(tend / interval + 1e-9), got["C++"][1], repeats))
print()
print("| loop | wall, median (range) [ms] |")
print("|---|---|")
print("| `reeving-pendulum` (C++) | %s |" % cell(walls["C++"]))
print("| Python: `step_to` + `observe_row` per report | %s |" % cell(walls["Python"]))
print("| ratio Python / C++ (per repeat) | %.3f (%.3f to %.3f) |" % (statistics.median(ratios), min(ratios), max(ratios)))
PY
