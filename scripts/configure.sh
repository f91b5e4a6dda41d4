#!/usr/bin/env bash
# Installs missing Debian packages and configures SimbodyReeving (Release) into build/.
# Used by build.sh (everything) and demo.sh (one demo's targets).
# A new build folder uses Ninja: it starts a library's compiles before the libraries it links are
# archived, which keeps both cores busy (Make waits per target). An existing folder keeps its generator.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install-deps.sh
generator=()
[ -f build/CMakeCache.txt ] || generator=(-G Ninja)
cmake -S . -B build "${generator[@]}" -DCMAKE_BUILD_TYPE=Release >/dev/null
