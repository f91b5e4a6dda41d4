#!/usr/bin/env bash
# Regenerates the tables of the topic documents (docs/*.md) from the benches, in place.
#
# Each generated table sits between two marker comments that name the command filling it:
#   <!-- BEGIN generated: COMMAND -->           run by default (finishes in seconds to a few minutes)
#   <!-- BEGIN generated --all: COMMAND -->     run only with --all (tens of minutes to an hour)
#   ...
#   <!-- END generated -->
# COMMAND runs from the repository root under bash. What replaces the lines between the markers:
#   - the Markdown table lines (lines starting with '|') of its standard output, consecutive tables
#     separated by one empty line; for the stress suite's GoogleTest binary (tests/simbody/test_stress)
#     its "[ stress ]" result lines (or the one-hour run's "[ long ]" lines), made into one table;
#   - otherwise the whole standard output, in a ```text block.
# A command that fails leaves its block unchanged and makes the script exit 1 at the end. A command
# quoted by several blocks runs once. Prose around the tables (and the noise stated beside each
# machine-dependent table) is not touched: re-read it when numbers move.
#
# The commands use the Release build in build/ (./scripts/build.sh); the script builds nothing
# itself (bench/cost.sh and bench/crane_speed.sh build their own targets).
#
# usage: scripts/regenerate-docs.sh [--all] [--only TEXT [--use-output FILE]] [--list] [FILE.md ...]
#   --all        also the long blocks (--all markers)
#   --only TEXT  only blocks whose command contains TEXT
#   --list       list the blocks (file, default or --all, command) and exit
#   --use-output FILE   do not run the selected command: take FILE as its standard output (a long
#                bench run separately, e.g. `CMD > FILE` on an idle machine); needs --only
#                selecting one command
#   FILE.md      documents to process (default docs/*.md)
# Exit status: 0 every selected block regenerated; 1 a command failed; 2 bad command line.
set -euo pipefail
cd "$(dirname "$0")/.."
all=0
only=
list=0
useOutput=
files=()
while (($#)); do
    case "$1" in
        --all) all=1 ;;
        --only) [[ $# -ge 2 ]] || { echo "regenerate-docs.sh: --only needs TEXT" >&2; exit 2; }; only=$2; shift ;;
        --list) list=1 ;;
        --use-output) [[ $# -ge 2 ]] || { echo "regenerate-docs.sh: --use-output needs FILE" >&2; exit 2; }; useOutput=$2; shift ;;
        -h | --help) sed -n '2,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
        -*) echo "regenerate-docs.sh: unknown option $1 (see --help)" >&2; exit 2 ;;
        *) files+=("$1") ;;
    esac
    shift
done
((${#files[@]})) || files=(docs/*.md)
[[ -z $useOutput || -n $only ]] || { echo "regenerate-docs.sh: --use-output needs --only" >&2; exit 2; }
command -v python3 >/dev/null || { echo "regenerate-docs.sh: python3 not found" >&2; exit 2; }

python3 - "$all" "$only" "$list" "$useOutput" "${files[@]}" <<'PY'
import re, subprocess, sys, time

run_all, only, list_only, use_output = sys.argv[1] == "1", sys.argv[2], sys.argv[3] == "1", sys.argv[4]
files = sys.argv[5:]
BEGIN = re.compile(r"^<!-- BEGIN generated( --all)?: (.*) -->\s*$")
END = "<!-- END generated -->"

def stress_table(out):
    """The stress suite's '[ stress ] NAME | integrator | steps N | wall X s | drift/KE0 D |
    constraint/weight C | RESULT' lines as one Markdown table."""
    rows = ["| run | integrator | steps | wall [s] | drift / KE0 | constraint / weight | result |",
            "|---|---|---:|---:|---:|---:|---|"]
    for line in out.splitlines():
        m = re.match(r"^\[ stress \] (\S+)\s*\| (\S+)\s*\| steps\s+(\d+) \| wall\s+([0-9.]+) s \| drift/KE0 (\S+) \| "
                     r"constraint/weight (\S+) \| (.*)$", line)
        if m:
            rows.append("| " + " | ".join(m.groups()) + " |")
    if len(rows) > 2:
        return rows
    rows = ["| simulated time [s] | max energy drift / KE0 | max sheave residual / weight | steps | wall [s] |",
            "|---:|---:|---:|---:|---:|"]
    for line in out.splitlines():
        m = re.match(r"^\[ long \] t = \s*(\S+) s  max drift / KE0 (\S+)  max sheave residual / weight (\S+)  "
                     r"steps (\d+)  wall (\S+) s$", line)
        if m:
            rows.append("| " + " | ".join(m.groups()) + " |")
    return rows if len(rows) > 2 else None

def format_output(cmd, out):
    if "test_stress" in cmd:
        rows = stress_table(out)
        if rows:
            return rows
    lines, last_table = [], False
    for line in out.splitlines():
        if line.startswith("|"):
            if lines and not last_table:
                lines.append("")
            lines.append(line.rstrip())
            last_table = True
        else:
            last_table = False
    if lines:
        return lines
    return ["```text"] + [l.rstrip() for l in out.strip("\n").splitlines()] + ["```"]

cache, failed = {}, []
for path in files:
    text = open(path).read().split("\n")
    out_lines, i, changed = [], 0, False
    while i < len(text):
        m = BEGIN.match(text[i])
        if not m:
            out_lines.append(text[i]); i += 1; continue
        long_, cmd = bool(m.group(1)), m.group(2)
        j = i + 1
        while j < len(text) and text[j].strip() != END:
            j += 1
        if j == len(text):
            print(f"{path}:{i + 1}: no '{END}' after this marker", file=sys.stderr)
            sys.exit(2)
        selected = (run_all or not long_) and (not only or only in cmd)
        if list_only:
            print(f"{path}:{i + 1}: {'--all  ' if long_ else 'default'}  {cmd}")
        if list_only or not selected:
            out_lines.extend(text[i:j + 1]); i = j + 1; continue
        if cmd not in cache and use_output:
            if cache:
                print(f"regenerate-docs.sh: --use-output: --only selects more than one command", file=sys.stderr)
                sys.exit(2)
            cache[cmd] = format_output(cmd, open(use_output).read())
        if cmd not in cache:
            t0 = time.time()
            print(f"regenerate-docs.sh: {cmd}", file=sys.stderr, flush=True)
            p = subprocess.run(["bash", "-c", cmd], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
            if p.returncode != 0:
                print(f"regenerate-docs.sh: FAILED (exit {p.returncode}): {cmd}\n{p.stderr[-2000:]}", file=sys.stderr)
                cache[cmd] = None
                failed.append(cmd)
            else:
                cache[cmd] = format_output(cmd, p.stdout)
                print(f"regenerate-docs.sh:   {time.time() - t0:.0f} s", file=sys.stderr, flush=True)
        body = cache[cmd]
        out_lines.append(text[i])
        out_lines.extend(text[i + 1:j] if body is None else body)
        out_lines.append(text[j])
        changed = changed or (body is not None and body != text[i + 1:j])
        i = j + 1
    if changed:
        open(path, "w").write("\n".join(out_lines))
        print(f"regenerate-docs.sh: rewrote {path}", file=sys.stderr)
if failed:
    sys.exit(1)
PY
