#!/usr/bin/env bash
# Installs every Debian package Galsculpt needs to build, run and test. Idempotent: packages
# already present are skipped by apt-get, and the package index is refreshed only when stale.
set -euo pipefail

# libopenblas0-pthread: an optimized BLAS/LAPACK behind Debian's alternatives, which CHOLMOD (the
# reference solver) then uses instead of the reference BLAS: 2.1 s instead of 6.5 s a frame on the
# hanging sphere (docs/benchmarks.md). Not the OpenMP build: inside this OpenMP program it ran
# twice as slow as the reference BLAS.
packages=(
  build-essential cmake pkg-config git
  libeigen3-dev libsuitesparse-dev nlohmann-json3-dev libtbb-dev
  libopenblas0-pthread
  libglfw3-dev libx11-dev libimgui-dev libstb-dev libassimp-dev
  libopengl-dev libegl-dev libgles-dev libegl1-mesa-dev libgl1-mesa-dri mesa-utils xvfb xauth
  libgtest-dev libgmock-dev libbenchmark-dev
  tetgen gnuplot-nox python3
  pybind11-dev python3-dev python3-numpy python3-pytest
)

sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "install-deps: not root and no sudo available" >&2; exit 1; }
  sudo_cmd=(sudo)
fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
