#!/usr/bin/env bash
# One command on a fresh Debian 12 machine: install dependencies, build, and open the default
# scene. With no display, galsculpt runs headless and says where it wrote its images.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
exec ./build/app/galsculpt "$@"
