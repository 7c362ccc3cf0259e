#!/usr/bin/env bash
# Configures and builds Galsculpt (Release) into ./build. Used by run-app.sh and run-tests.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc 2>/dev/null || echo 2)
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release ${GALSCULPT_CMAKE_ARGS:-}
cmake --build build -j "$jobs"
