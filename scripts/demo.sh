#!/usr/bin/env bash
# Installs missing Debian packages, builds only what the demo needs (the plugin and the demo
# executable: no tests, no benchmarks) and runs a bundled demo with its defaults:
#   ./scripts/demo.sh [ARGS...]        the pendulum demo (the paper's Table 1 study), out/pendulum
#   ./scripts/demo.sh crane [ARGS...]  the gantry-crane demo (lift, traverse, lower), out/crane
# Extra arguments go to the demo; ./scripts/demo.sh --help and ./scripts/demo.sh crane --help list
# the demo's options.
set -euo pipefail
cd "$(dirname "$0")/.."
demo=reeving-pendulum
if [ "${1:-}" = crane ]; then
    demo=reeving-crane
    shift
fi
./scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$(nproc)" --target "$demo"
exec "./build/examples/$demo" "$@"
