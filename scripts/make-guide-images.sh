#!/usr/bin/env bash
# Renders the pictures of docs/user-guide.md and the README from the shipped scripts:
#   - the window itself (panels, cursor, views) under Xvfb, in real time as a user runs it, driven
#     by docs/images/guide_overview_input.json;
#   - the sculpted face (assets/scripts/sculpted_face.json) through `galsculpt play`;
#   - the knife cuts of docs/surface.md and the README (docs/images/knife_cut_apart.json,
#     assets/scripts/sphere_cut.json): the "after" pictures (the "before" ones were rendered by
#     the same commands at commit a18cfc0, before crack faces followed the blade);
#   - with --armadillo, the armadillo's arm pulled off (needs scripts/fetch-cgal-meshes.sh; ~5 min).
# Run from anywhere after scripts/build.sh; writes into docs/images/.
set -euo pipefail
cd "$(dirname "$0")/.."
bin=build/app/galsculpt
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

GALSCULPT_RECOVERY_DIR="$tmp/recovery" xvfb-run -a -s "-screen 0 1280x800x24" \
  "$bin" open assets/scenes/default.json --no-recovery --autosave 0 --size 1100x700 \
  --input-script docs/images/guide_overview_input.json

"$bin" play assets/scripts/sculpted_face.json --out "$tmp/face" --png-every 1000 --size 800x500
cp "$tmp/face/final.png" docs/images/sculpted_face.png

"$bin" play docs/images/knife_cut_apart.json --out "$tmp/knife" --png-every 1000 --size 640x400
cp "$tmp/knife/final.png" docs/images/knife_cut_after.png
"$bin" play assets/scripts/sphere_cut.json --out "$tmp/sphere_cut" --png-every 1000 --size 640x400
cp "$tmp/sphere_cut/final.png" docs/images/sphere_cut_after.png

if [ "${1:-}" = "--armadillo" ]; then
  "$bin" play assets/scripts/armadillo_arm_pull.json --out "$tmp/arm" --png-every 1000 --size 960x600
  cp "$tmp/arm/final.png" docs/images/armadillo_arm_pull.png
fi
echo "wrote docs/images/"
