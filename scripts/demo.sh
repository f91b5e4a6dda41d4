#!/usr/bin/env bash
# Installs missing Debian packages, builds, and runs the pendulum demo (the paper's Table 1 study)
# with its defaults: outputs and figures in out/pendulum. Extra arguments go to reeving-pendulum
# (see ./build/examples/reeving-pendulum --help).
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/build.sh
./build/examples/reeving-pendulum "$@"
