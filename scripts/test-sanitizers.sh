#!/usr/bin/env bash
# Builds the project with AddressSanitizer + UndefinedBehaviorSanitizer into build-asan/ and runs the
# unit, simulation and demo tests under them (not the `stress` label; not the `package` test, whose
# outside consumer project does not link the sanitizer runtimes). Any report fails the run: ASan and
# UBSan abort on the first error. Takes longer than ./scripts/test.sh (about 3x the test time).
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install-deps.sh
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSIMBODYREEVING_SANITIZE=ON \
      -DSIMBODYREEVING_BUILD_BENCHMARKS=OFF >/dev/null
cmake --build build-asan -j"$(nproc)"
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:strict_string_checks=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
ctest --test-dir build-asan --output-on-failure -j"$(nproc)" -LE "stress|package"
