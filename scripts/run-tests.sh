#!/usr/bin/env bash
# One command on a fresh Debian 12 machine: install dependencies, build, and run every test
# (CTest labels: unit, render, slow). Extra arguments go to ctest (e.g. -L unit).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
cd build
# Generated meshes are cached inside the build tree, never in the user's cache.
export GALSCULPT_CACHE_DIR="$PWD/test-cache"
# ctest already runs tests side by side; the solver's threads on top of that oversubscribe the
# cores (its default count honours OMP_NUM_THREADS, docs/cli.md "Threads"). Tests that check
# threading set their thread counts themselves.
export OMP_NUM_THREADS=${OMP_NUM_THREADS:-1}
# The same for OpenBLAS's own threads (CHOLMOD's BLAS): they spin while waiting.
export OPENBLAS_NUM_THREADS=${OPENBLAS_NUM_THREADS:-1}
ctest --output-on-failure -j "$(nproc 2>/dev/null || echo 2)" "$@"
