#!/usr/bin/env bash
# Installs missing Debian packages, builds only what the demo needs (the plugin and the demo
# executable: no tests, no benchmarks) and runs a bundled demo with its defaults:
#   ./scripts/demo.sh [ARGS...]        the pendulum demo (the paper's Table 1 study), out/pendulum
#   ./scripts/demo.sh crane [ARGS...]  the gantry-crane demo (lift, traverse, lower), out/crane
#   ./scripts/demo.sh elevator [ARGS...]  the traction-elevator demo (EN 81-50 traction checks), out/elevator
#   ./scripts/demo.sh boom-crane [ARGS...]  the boom-crane demo (lift, slew while luffing, lower), out/boom-crane
# Extra arguments go to the demo; ./scripts/demo.sh --help, ./scripts/demo.sh crane --help,
# ./scripts/demo.sh elevator --help and ./scripts/demo.sh boom-crane --help list
# the demo's options.
set -euo pipefail
cd "$(dirname "$0")/.."
demo=reeving-pendulum
if [ "${1:-}" = crane ]; then
    demo=reeving-crane
    shift
elif [ "${1:-}" = elevator ]; then
    demo=reeving-elevator
    shift
elif [ "${1:-}" = boom-crane ]; then
    demo=reeving-boom-crane
    shift
fi
./scripts/configure.sh
cmake --build build -j"$(nproc)" --target "$demo"
exec "./build/examples/$demo" "$@"
