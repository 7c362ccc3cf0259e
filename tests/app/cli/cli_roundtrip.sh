#!/usr/bin/env bash
# End to end through the real binary: a closed surface from outside the repository goes through
# import -> tet mesh -> info -> export, and a broken file gives exit 3 with file:line.
set -euo pipefail
galsculpt=$1
work=$2
rm -rf "$work" && mkdir -p "$work"
cd "$work"

# A surface "from outside": written by the generator as STL, then used like any user file.
"$galsculpt" mesh generate charpy bar.stl >/dev/null
"$galsculpt" mesh info bar.stl | grep -q "watertight: yes"
"$galsculpt" mesh import bar.stl bar.node --tets 4000 2>import.log
tets=$("$galsculpt" mesh info bar.node | sed -n 's/^tets: //p')
if [ "$tets" -lt 3400 ] || [ "$tets" -gt 4600 ]; then echo "got $tets tets, wanted 4000 +-15 %"; exit 1; fi
"$galsculpt" mesh info bar.node | grep -q "watertight: yes"
"$galsculpt" mesh info bar.node | grep -q "pieces: 1"
for out in bar_surface.obj bar_surface.ply bar_surface.stl bar_surface.gltf bar.msh bar.vtk; do
  "$galsculpt" mesh convert bar.node "$out" >/dev/null
  test -s "$out"
done
"$galsculpt" mesh info bar_surface.obj | grep -q "watertight: yes"

set +e
"$galsculpt" mesh info "$(dirname "$0")/../../data/broken/index_out_of_range.node" 2>err.txt
code=$?
set -e
[ "$code" -eq 3 ] || { echo "expected exit 3, got $code"; exit 1; }
grep -q "index_out_of_range.ele:2: vertex index 9 out of range" err.txt
echo "cli round trip ok ($tets tets)"
