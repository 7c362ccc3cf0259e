#!/usr/bin/env bash
# Packs what scripts/device_check.sh needs on a device machine that has the CUDA toolkit but none
# of galsculpt's Debian libraries: galsculpt and gpu_tests from BUILD (built with the CUDA
# backend), the shared libraries they load (less the C library itself; the C++ runtime apart, used
# only where the machine's own is older), tetgen, and the meshes of the bench scenes and the GPU
# tests, generated here into the pack's cache (the armadillo and human meshes need
# scripts/fetch-cgal-meshes.sh's archive), and the bench references kept in REFS (`bench
# --reference-dir REFS` run here: the reference runs on the CPU, seconds a frame). Writes OUT
# (an .tar.xz).
#   scripts/device_pack.sh BUILD OUT [REFS]
set -euo pipefail
build=$1
out=$2
refs=${3:-}
cd "$(dirname "$0")/.."
stage=$(mktemp -d)
trap 'rm -rf "$stage"' EXIT
mkdir -p "$stage/bin" "$stage/lib" "$stage/libcxx" "$stage/cache"
cp "$build/app/galsculpt" "$build/tests/gpu_tests" "$(command -v tetgen)" "$stage/bin/"
strip "$stage/bin/galsculpt" "$stage/bin/gpu_tests"
for f in $( (ldd "$build/app/galsculpt" && ldd "$build/tests/gpu_tests") | awk '$3 ~ /^\// {print $3}' | sort -u); do
  case $(basename "$f") in
    libc.so* | libm.so* | libpthread* | libdl.so* | ld-linux* | librt*) ;;
    libstdc++* | libgcc_s*) cp -L "$f" "$stage/libcxx/" ;;
    *) cp -L "$f" "$stage/lib/" ;;
  esac
done
cache=${GALSCULPT_CACHE_DIR:-${XDG_CACHE_HOME:-$HOME/.cache}/galsculpt}
# The bench scenes' meshes come from the user's cache when there, else they are made now.
export GALSCULPT_CACHE_DIR=$stage/cache
[ -d "$cache/cgal" ] && cp -r "$cache/cgal" "$stage/cache/"
[ -d "$cache/meshes" ] && mkdir -p "$stage/cache/meshes" && cp "$cache"/meshes/* "$stage/cache/meshes/"
for scene in hanging_sphere charpy human armadillo steak clay_head; do
  "$build/app/galsculpt" scene check "assets/scenes/$scene.json" --load-mesh >/dev/null
done
# The GPU tests' smaller meshes.
[ -d "$build/test-cache/meshes" ] && cp "$build"/test-cache/meshes/{sphere-6000-r0.1,charpy-8000}.* \
  "$stage/cache/meshes/" 2>/dev/null || true
[ -n "$refs" ] && cp -r "$refs" "$stage/refs"
tar -C "$stage" -cf - . | xz -T0 -6 >"$out.tmp"
mv "$out.tmp" "$out"
ls -la "$out"
