#!/usr/bin/env bash
# The armadillo and human-figure scenes use closed meshes from Debian's libcgal-demo package
# (its data archive). This installs the package, unpacks armadillo.off and homer.off into the
# galsculpt cache, and (with --mesh) tetrahedralizes them for the shipped scenes.
set -euo pipefail
cd "$(dirname "$0")/.."
cache=${GALSCULPT_CACHE_DIR:-${XDG_CACHE_HOME:-$HOME/.cache}/galsculpt}
archive=/usr/share/doc/libcgal-dev/data.tar.gz

if [ ! -f "$archive" ]; then
  sudo_cmd=()
  [ "$(id -u)" -ne 0 ] && sudo_cmd=(sudo)
  export DEBIAN_FRONTEND=noninteractive
  "${sudo_cmd[@]}" apt-get update -qq
  "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends libcgal-demo
fi

mkdir -p "$cache/cgal"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
tar -xzf "$archive" -C "$tmp" data/meshes/armadillo.off data/meshes/homer.off
for name in armadillo homer; do
  mv "$tmp/data/meshes/$name.off" "$cache/cgal/$name.off.tmp"
  mv "$cache/cgal/$name.off.tmp" "$cache/cgal/$name.off"
  echo "fetch-cgal-meshes: $cache/cgal/$name.off"
done

if [ "${1:-}" = "--mesh" ]; then
  for scene in human armadillo; do
    ./build/app/galsculpt scene check "assets/scenes/$scene.json" --load-mesh
  done
fi
