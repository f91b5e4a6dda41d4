#!/usr/bin/env bash
# Installs missing Debian packages, builds, and runs every test through ctest (the `stress` label,
# if present, is excluded: run it with `ctest --test-dir build -L stress`).
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/build.sh
ctest --test-dir build --output-on-failure -j"$(nproc)" -LE stress
