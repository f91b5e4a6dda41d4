#!/usr/bin/env bash
# Throughput of reeving-study (docs/studies.md, section "Throughput"), in one run so that the
# figures compare as ratios:
#   1. cases per second of a fixed small study (24 cases of reeving-pendulum --axial-modes 1
#      --t-end 20, vx0 from 0.5 to 2 m/s, about 0.3 s each) run serially (one process running
#      cases), under `mpirun --oversubscribe --bind-to none -n 2` (rank 0 hands out cases: one rank
#      runs them) and `-n 3` (two ranks run them), and under `mpirun --oversubscribe -n 2` with
#      OpenMPI's default binding (each rank, and the cases it starts, bound to a core of its own);
#      REPEATS runs of each, interleaved (serial, -n 2, -n 3, -n 2 bound; then -n 2, -n 3, -n 2
#      bound, serial; ...) so that the machine's load hits all alike; medians. Two rates: over the
#      runner's own wall time (summary.json wall_seconds: from the first case handed out to the
#      last row) and over the whole command (process and MPI start-up and the --check of every
#      case included).
#   2. the scheduling overhead per case: a study of 40 trivial cases (reeving-pendulum
#      --axial-modes 0 --t-end 0.01, well under 0.1 s) against the same 40 demo command lines (from
#      the study's --dry-run) run one after the other by python3 (fork and exec, as the runner),
#      before and after the study (the mean of the two is the baseline), each in a fresh folder
#      removed afterwards as the runner does; per case: the runner's wall minus the direct wall, the
#      whole command's minus the direct wall (the --check phase and start-up included), the
#      runner's wall minus its children's walls (its own time between cases), and under
#      `mpirun -n 2 --bind-to none` (one rank running cases) minus serial (the hand-out by rank 0).
#      Interleaved, medians.
#   3. how the wall time of each bundled study (studies/elevator-traction,
#      studies/crane-dynamic-factor) divides over its cases, from its results.csv (the wall_seconds
#      column: each case's demo run, start to end): cases, total, median, max, the share of the
#      total taken by the slowest 10 % of cases and by the slowest case, failed cases, and the same
#      split by the study's first varied parameter. The studies run serially into out/<name>/
#      (minutes: the elevator's 270 cases take about two); --reuse takes out/<name>/results.csv
#      when it is there, --skip-bundled leaves this part out.
# Prints Markdown tables with the date, nproc, the CPU model and the load average before and after.
# The absolute figures depend on what else runs on the machine; compare ratios of one run.
#
# usage: bench/study_throughput.sh [--skip-bundled] [--reuse] [--repeats N] [--no-build] [BUILD_DIR]
#   --repeats N: runs of each configuration (default 3)
#   --no-build: run the programs in BUILD_DIR as they are
#   BUILD_DIR: a configured build folder (default build); reeving-study and the three demos are
#   built there first (through `flock /tmp/sr-build.lock`, so concurrent builds on a shared machine
#   wait for each other). Needs python3; mpirun (OpenMPI) and a build with
#   SIMBODYREEVING_STUDY_MPI=ON for the MPI rows (left out otherwise, with a note).
# Takes about 1.5 minutes per repeat with --skip-bundled or --reuse on the shared 2-core machine,
# plus the bundled studies' own time (about 2 minutes).
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD

skip_bundled=0
reuse=0
no_build=0
repeats=3
build=build
while [ $# -gt 0 ]; do
    case "$1" in
        --skip-bundled) skip_bundled=1 ;;
        --reuse) reuse=1 ;;
        --repeats) repeats=$2; shift ;;
        --no-build) no_build=1 ;;
        -h | --help) sed -n '2,/^set -euo/p' "$0" | sed '$d' | sed 's/^# \{0,1\}//'; exit 0 ;;
        -*) echo "study_throughput.sh: unknown option $1 (see --help)" >&2; exit 2 ;;
        *) build=$1 ;;
    esac
    shift
done
[[ $repeats =~ ^[1-9][0-9]*$ ]] || { echo "study_throughput.sh: --repeats: '$repeats' is not a count" >&2; exit 2; }
[ -f "$build/CMakeCache.txt" ] || { echo "study_throughput.sh: $build is not a configured build folder" >&2; exit 2; }
command -v python3 >/dev/null || { echo "study_throughput.sh: python3 not found" >&2; exit 1; }
build=$(cd "$build" && pwd)

if [ "$no_build" -eq 0 ]; then
    flock /tmp/sr-build.lock cmake --build "$build" --target reeving-study reeving-pendulum reeving-elevator \
        reeving-crane -- -j2 >/dev/null
fi
study_exe=$build/examples/reeving-study
demo_dir=$build/examples

mpi=1
mpi_note=""
if ! grep -q '^SIMBODYREEVING_STUDY_MPI:BOOL=ON' "$build/CMakeCache.txt"; then
    mpi=0; mpi_note="reeving-study is built without MPI (SIMBODYREEVING_STUDY_MPI=OFF): no MPI rows"
elif ! command -v mpirun >/dev/null; then
    mpi=0; mpi_note="no mpirun: no MPI rows"
fi
if [ "$(id -u)" -eq 0 ]; then
    export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
fi

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
raw=$tmp/raw.tsv   # kind config repeat cases command_wall runner_wall case_wall
: >"$raw"

cat >"$tmp/throughput.yaml" <<'EOF'
description: reeving-study throughput, 24 pendulum cases of about 0.3 s
scene: pendulum
fixed: {axial-modes: 1, t-end: 20}
vary:
  vx0: {linear: {from: 0.5, to: 2, count: 24}}
metrics: [steps, max_energy_drift_J]
EOF
cat >"$tmp/trivial.yaml" <<'EOF'
description: reeving-study scheduling overhead, 40 trivial pendulum cases
scene: pendulum
fixed: {axial-modes: 0, t-end: 0.01}
vary:
  vx0: {linear: {from: 0.5, to: 2, count: 40}}
metrics: [steps]
EOF

now() { date +%s.%N; }

# run_study KIND STUDY_FILE CONFIG REPEAT: one run of the study, one line in $raw. CONFIG: serial
# (no mpirun), n2 and n3 (mpirun -n 2 or 3, --bind-to none: every process, the cases included, free
# to run on any core, as in the serial run) or n2-bound (mpirun -n 2 with OpenMPI's default binding:
# with no more ranks than cores each rank is bound to a core, and the cases it starts inherit it).
run_study() {
    local kind=$1 file=$2 config=$3 rep=$4 out=$tmp/out-$1-$3-$4 t0 t1 status=0
    local cmd=("$study_exe" "$file" --out "$out" --quiet)
    case "$config" in
        n2) cmd=(mpirun --oversubscribe --bind-to none -n 2 "${cmd[@]}") ;;
        n3) cmd=(mpirun --oversubscribe --bind-to none -n 3 "${cmd[@]}") ;;
        n2-bound) cmd=(mpirun --oversubscribe -n 2 "${cmd[@]}") ;;
    esac
    t0=$(now)
    "${cmd[@]}" >"$out.log" 2>&1 || status=$?
    t1=$(now)
    if [ "$status" -ne 0 ]; then
        echo "study_throughput.sh: ${cmd[*]} exited with status $status:" >&2
        cat "$out.log" >&2
        exit 1
    fi
    python3 - "$out/summary.json" "$kind" "$config" "$rep" "$t0" "$t1" >>"$raw" <<'EOF'
import json, sys
s = json.load(open(sys.argv[1]))
print(sys.argv[2], sys.argv[3], sys.argv[4], s["cases_run"], float(sys.argv[6]) - float(sys.argv[5]),
      s["wall_seconds"], s["case_wall_seconds"], sep="\t")
EOF
    rm -rf "$out"
}

# run_direct REPEAT: the trivial study's demo command lines run one after the other from python3
# (fork and exec, as the runner does), each in a fresh folder removed afterwards, stdout and stderr
# to files there (as the runner does with its case folders).
"$study_exe" "$tmp/trivial.yaml" --dry-run | sed -n 's/^    reeving-pendulum //p' >"$tmp/trivial.args"
n_trivial=$(wc -l <"$tmp/trivial.args")
[ "$n_trivial" -eq 40 ] || { echo "study_throughput.sh: --dry-run listed $n_trivial cases, not 40" >&2; exit 1; }
run_direct() {
    python3 - "$demo_dir/reeving-pendulum" "$tmp/trivial.args" "$tmp" "$1" >>"$raw" <<'PY'
import os, shutil, subprocess, sys, tempfile, time
program, args_file, tmp, rep = sys.argv[1:5]
lines = [l.split() for l in open(args_file) if l.strip()]
start = time.perf_counter()
for args in lines:
    d = tempfile.mkdtemp(dir=tmp, prefix="direct.")
    with open(os.path.join(d, "stdout.txt"), "w") as out, open(os.path.join(d, "stderr.txt"), "w") as err:
        status = subprocess.call([program] + [a.replace("CASE_DIR", d + "/out") for a in args], stdout=out, stderr=err)
    if status != 0: sys.exit(f"study_throughput.sh: {program} {' '.join(args)}: exit status {status}")
    shutil.rmtree(d)
wall = time.perf_counter() - start
print("direct", "serial", rep, len(lines), wall, wall, wall, sep="\t")
PY
}

load_before=$(cut -d' ' -f1-3 /proc/loadavg)
started=$(date -u '+%Y-%m-%d %H:%M UTC')
configs=(serial)
[ "$mpi" -eq 1 ] && configs=(serial n2 n3 n2-bound)
for rep in $(seq "$repeats"); do
    echo "study_throughput.sh: repeat $rep of $repeats (load average $(cut -d' ' -f1 /proc/loadavg))" >&2
    # Each repeat starts one configuration further on (serial, n2, n3, n2-bound; then n2, n3,
    # n2-bound, serial; ...): none always runs first, next to the overhead runs.
    for i in "${!configs[@]}"; do
        config=${configs[$(((i + rep - 1) % ${#configs[@]}))]}
        run_study throughput "$tmp/throughput.yaml" "$config" "$rep"
    done
    # The direct runs before and after the study's (their mean is the baseline: drifts in the
    # machine's load between them cancel to first order).
    run_direct "$rep"
    run_study trivial "$tmp/trivial.yaml" serial "$rep"
    [ "$mpi" -eq 1 ] && run_study trivial "$tmp/trivial.yaml" n2 "$rep"
    run_direct "$rep"
done
load_mid=$(cut -d' ' -f1-3 /proc/loadavg)

# The bundled studies: serially into out/<name>/, or the results.csv there with --reuse.
bundled=()
if [ "$skip_bundled" -eq 0 ]; then
    for name in elevator-traction crane-dynamic-factor; do
        out=$root/out/$name
        if [ "$reuse" -eq 1 ] && [ -f "$out/results.csv" ]; then
            echo "study_throughput.sh: $name: reusing $out/results.csv" >&2
            bundled+=("$name|$out|reused")
            continue
        fi
        echo "study_throughput.sh: $name: running serially into $out (load average $(cut -d' ' -f1 /proc/loadavg))" >&2
        t0=$(now)
        status=0
        "$study_exe" "studies/$name" --out "$out" --quiet >"$tmp/$name.log" 2>&1 || status=$?
        t1=$(now)
        # Exit status 1: some cases failed or timed out; their rows are in results.csv all the same.
        if [ "$status" -gt 1 ]; then
            echo "study_throughput.sh: reeving-study studies/$name exited with status $status:" >&2
            cat "$tmp/$name.log" >&2
            exit 1
        fi
        bundled+=("$name|$out|run now, $(python3 -c "print(f'{$t1 - $t0:.0f}')") s for the whole command")
    done
fi
load_after=$(cut -d' ' -f1-3 /proc/loadavg)

cpu="$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -n 1) (cpu family $(sed -n \
    's/^cpu family[[:space:]]*: //p' /proc/cpuinfo | head -n 1), model $(sed -n 's/^model[[:space:]]*: //p' \
    /proc/cpuinfo | head -n 1), $(sed -n 's/^cpu MHz[[:space:]]*: \([0-9]*\).*/\1/p' /proc/cpuinfo | head -n 1) MHz)"
grep -qw hypervisor /proc/cpuinfo && cpu="$cpu, a virtual machine"
python3 - "$raw" "$started" "$(nproc)" "$cpu" \
    "$load_before" "$load_mid" "$load_after" "$repeats" "$mpi_note" "${bundled[@]}" <<'EOF'
import csv, json, os, statistics, sys

raw, started, nproc, cpu, load_before, load_mid, load_after, repeats, mpi_note = sys.argv[1:10]
bundled = sys.argv[10:]
runs = {}  # (kind, config) -> one dict per repeat, in the order of the repeats
for line in open(raw):
    kind, config, rep, cases, command, runner, case_wall = line.split("\t")
    r = dict(rep=int(rep), cases=int(cases), command=float(command), runner=float(runner), case_wall=float(case_wall))
    same = runs.setdefault((kind, config), [])
    if same and same[-1]["rep"] == r["rep"]:  # the second direct run of a repeat: the mean of the two
        for field in ("command", "runner", "case_wall"): same[-1][field] = (same[-1][field] + r[field]) / 2
    else:
        same.append(r)

def values(key, field, per_case=False, rate=False):
    """The figure of each repeat, in the order of the repeats."""
    out = []
    for r in runs[key]:
        v = r[field]
        if rate: v = r["cases"] / v
        elif per_case: v = v / r["cases"]
        out.append(v)
    return out

def med(key, field, per_case=False, rate=False):
    return statistics.median(values(key, field, per_case, rate))

def spread(v, fmt):
    return f"{fmt(statistics.median(v))} ({fmt(min(v))} to {fmt(max(v))})"

print(f"Measured {started} with bench/study_throughput.sh: nproc {nproc}, {cpu}; "
      f"load average (1, 5, 15 min) {load_before} before, {load_mid} after the throughput runs, "
      f"{load_after} at the end. The machine is shared (other builds may run): the absolute figures "
      f"move with its load, the ratios of one run are what compares. Medians of {repeats} runs, "
      f"interleaved (in parentheses: the smallest and largest of the {repeats}).")
if mpi_note: print(f"\nNote: {mpi_note}.")

print("\n### Cases per second (24 pendulum cases, --axial-modes 1 --t-end 20)\n")
print("| run | ranks running cases | cases/s (runner wall) | vs serial, same repeat | cases/s (whole command) "
      "| vs serial, same repeat | case wall, mean [s] |")
print("|---|---|---|---|---|---|---|")
labels = {"serial": ("serial", 1), "n2": ("mpirun -n 2 --bind-to none", 1), "n3": ("mpirun -n 3 --bind-to none", 2),
          "n2-bound": ("mpirun -n 2 (OpenMPI's default: ranks bound to cores)", 1)}
two = lambda x: f"{x:.2f}"
for config, (label, workers) in labels.items():
    key = ("throughput", config)
    if key not in runs: continue
    rate, rate_cmd = values(key, "runner", rate=True), values(key, "command", rate=True)
    rate1, rate1_cmd = values(("throughput", "serial"), "runner", rate=True), values(("throughput", "serial"), "command", rate=True)
    print(f"| {label} | {workers} | {spread(rate, two)} | {spread([a / b for a, b in zip(rate, rate1)], two)} "
          f"| {spread(rate_cmd, two)} | {spread([a / b for a, b in zip(rate_cmd, rate1_cmd)], two)} "
          f"| {med(key, 'case_wall', per_case=True):.3f} |")

print("\n### Scheduling overhead per case (40 trivial pendulum cases, --axial-modes 0 --t-end 0.01)\n")
ms = lambda x: f"{1000 * x:.1f}"
def per_case(key, field):
    return values(key, field, per_case=True)
def diff(a, b):
    return [x - y for x, y in zip(a, b)]
direct = per_case(("direct", "serial"), "command")
study_runner, study_command = per_case(("trivial", "serial"), "runner"), per_case(("trivial", "serial"), "command")
print("| per case | median (range) [ms] |")
print("|---|---|")
print(f"| the demo run directly, one after the other (mean of the runs before and after the study's) | {spread(direct, ms)} |")
print(f"| the same cases in reeving-study, runner wall | {spread(study_runner, ms)} |")
print(f"| the same, whole command (start-up and every case's --check included) | {spread(study_command, ms)} |")
print(f"| overhead: runner wall - direct, same repeat | {spread(diff(study_runner, direct), ms)} |")
print(f"| overhead: whole command - direct, same repeat | {spread(diff(study_command, direct), ms)} |")
print(f"| the runner's own time between cases: runner wall - its cases' walls | "
      f"{spread(diff(study_runner, per_case(('trivial', 'serial'), 'case_wall')), ms)} |")
if ("trivial", "n2") in runs:
    mpi_runner = per_case(("trivial", "n2"), "runner")
    print(f"| under mpirun -n 2 --bind-to none (one rank running cases), runner wall | {spread(mpi_runner, ms)} |")
    print(f"| overhead of the MPI hand-out: -n 2 - serial, runner walls, same repeat | {spread(diff(mpi_runner, study_runner), ms)} |")

if bundled:
    print("\n### The bundled studies' wall time over their cases (results.csv, wall_seconds)\n")
    print("| study | source | cases | total [s] | median [s] | max [s] | slowest 10 % of cases | slowest case | failed |")
    print("|---|---|---|---|---|---|---|---|---|")
    groups = []
    for item in bundled:
        name, out, source = item.split("|")
        with open(os.path.join(out, "results.csv"), newline="") as f:
            rows = list(csv.DictReader(f))
        walls = sorted((float(r["wall_seconds"]) for r in rows), reverse=True)
        total = sum(walls)
        top = max(1, round(len(walls) / 10))
        failed = sum(r["status"] != "ok" for r in rows)
        try:
            s = json.load(open(os.path.join(out, "summary.json")))
            source += f"; {s['ranks']} rank(s), runner wall {s['wall_seconds']:.0f} s"
        except (OSError, KeyError, ValueError):
            pass
        print(f"| {name} | {source} | {len(walls)} | {total:.1f} | {statistics.median(walls):.3f} | {walls[0]:.2f} "
              f"| {100 * sum(walls[:top]) / total:.0f} % ({top} cases) | {100 * walls[0] / total:.0f} % | {failed} |")
        first = list(rows[0].keys())[1]
        split = {}
        for r in rows:
            split.setdefault(r[first], []).append(float(r["wall_seconds"]))
        groups.append((name, first, split, total))
    for name, first, split, total in groups:
        print(f"\n{name}, by {first}:\n")
        print(f"| {first} | cases | total [s] | share | median [s] | max [s] |")
        print("|---|---|---|---|---|---|")
        for value, w in split.items():
            print(f"| {value} | {len(w)} | {sum(w):.1f} | {100 * sum(w) / total:.0f} % | {statistics.median(w):.3f} "
                  f"| {max(w):.2f} |")
EOF
