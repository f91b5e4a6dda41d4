#!/usr/bin/env bash
# Runs a parameter study (docs/studies.md): installs missing Debian packages, builds reeving-study
# and the demo its study file names (nothing else), then runs the study:
#   ./scripts/study.sh studies/elevator-traction [ARGS...]                    serially
#   MPIRUN="mpirun -n 4" ./scripts/study.sh studies/elevator-traction [ARGS...]   under MPI
# STUDY is a folder holding study.yaml or a .yaml file; the outputs go to out/<name>
# (results.csv, summary.json, figures/) unless --out DIR is given. Extra arguments go to
# reeving-study: --out DIR, --resume, --dry-run, --quiet (reeving-study --help).
# With MPIRUN (OpenMPI): as root the two OMPI_ALLOW_RUN_AS_ROOT variables are set, and more ranks
# than cores are allowed (OMPI_MCA_rmaps_base_oversubscribe=1; rank 0 only hands out cases).
set -euo pipefail
cd "$(dirname "$0")/.."
if [ $# -lt 1 ]; then
    sed -n '2,11p' "$0" | sed 's/^# \{0,1\}//' >&2
    exit 2
fi
study=$1
shift
file=$study
[ -d "$study" ] && file=$study/study.yaml
[ -f "$file" ] || { echo "study.sh: $file: no such study file" >&2; exit 2; }
scene=$(sed -n 's/^scene:[[:space:]]*\([a-z]*\).*/\1/p' "$file" | head -n 1)
case "$scene" in
    pendulum | crane | elevator) ;;
    *) echo "study.sh: $file: no 'scene:' line naming pendulum, crane or elevator" >&2; exit 2 ;;
esac
./scripts/configure.sh
if [ -n "${MPIRUN:-}" ]; then
    cmake -S . -B build -DSIMBODYREEVING_STUDY_MPI=ON > /dev/null
fi
cmake --build build -j"$(nproc)" --target reeving-study "reeving-$scene"
if [ -n "${MPIRUN:-}" ]; then
    if [ "$(id -u)" -eq 0 ]; then
        export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
    fi
    export OMPI_MCA_rmaps_base_oversubscribe=${OMPI_MCA_rmaps_base_oversubscribe:-1}
    # shellcheck disable=SC2086  # MPIRUN is a command with its arguments
    exec $MPIRUN ./build/examples/reeving-study "$study" "$@"
fi
exec ./build/examples/reeving-study "$study" "$@"
