#!/usr/bin/env bash
# Installs missing Debian packages, builds, and runs a bundled demo with its defaults:
#   ./scripts/demo.sh [ARGS...]        the pendulum demo (the paper's Table 1 study), out/pendulum
#   ./scripts/demo.sh crane [ARGS...]  the gantry-crane demo (lift, traverse, lower), out/crane
# Extra arguments go to the demo (see ./build/examples/reeving-pendulum --help and
# ./build/examples/reeving-crane --help).
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/build.sh
if [ "${1:-}" = crane ]; then
    shift
    exec ./build/examples/reeving-crane "$@"
fi
exec ./build/examples/reeving-pendulum "$@"
