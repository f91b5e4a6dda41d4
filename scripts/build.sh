#!/usr/bin/env bash
# Configures and builds SimbodyReeving (Release) into build/. Used by demo.sh and test.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/configure.sh
cmake --build build -j"$(nproc)"
