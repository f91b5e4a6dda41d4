#!/usr/bin/env bash
# Installs missing Debian packages, builds, and runs the demo. Extra arguments go to the demo.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/build.sh
./build/examples/span-element-tour "$@"
