#!/usr/bin/env python3
"""Speed against the error in motion, several scenes in one plot (gnuplot PNG) and a Markdown
table, from `galsculpt bench --json` files (one or more scenes each).

Each scene's paper preset and converged default are joined by an arrow (old setting -> new
default); a scene's own setting, when it differs, is a third point. Error: the bench's
rel_position_error_motion (the largest distance to the reference at its motion_frame, over the
reference's largest displacement), in per cent.

usage: scripts/plot-speed-error.py OUT.png BENCH.json [BENCH.json ...]
"""
import json
import os
import subprocess
import sys
import tempfile

from speed_error_plot import gnuplot_header


def rows_of(paths):
    rows = []
    for path in paths:
        for r in json.load(open(path))["results"]:
            if "error" not in r:
                rows.append(r)
    return rows


def table(rows):
    print("| scene | tets | setting | ms/frame | p95 ms | fps | error in motion % (frame) | "
          "error at end % | Newton / CG per frame | frames not converged |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    seen = set()
    for r in rows:
        ref = r["solver"] == "reference"
        preset = r.get("preset", "")
        if not ref and (r["scene"], preset) in seen:
            setting = f"own ({r.get('newton_iters')} Newton, PCG {r.get('pcg_tolerance')})"
        else:
            setting = "reference" if ref else f"{preset} {r['grid']}"
            seen.add((r["scene"], preset))
        motion = "—" if ref else f"{100 * r['rel_position_error_motion']:.3g} ({r['motion_frame']})"
        end = "—" if ref else f"{100 * r['rel_position_error']:.3g}"
        iters = f"{r['newton_iters_mean']:.2f} / {r['cg_iters_mean']:.1f}"
        print(f"| {r['scene']} | {r['tets']} | {setting} | "
              f"{r['ms_per_frame']:.1f} | {r['ms_p95']:.1f} | {r['fps']:.2f} | {motion} | {end} | "
              f"{iters} | {r['unconverged_frames']} of {r['frames']} |")


def plot(rows, out):
    with tempfile.TemporaryDirectory() as tmp:
        points = {"paper": [], "converged": [], "own": []}
        arrows = []
        scenes = sorted({r["scene"] for r in rows}, key=lambda s: [r["scene"] for r in rows].index(s))
        for scene in scenes:
            mg = [r for r in rows if r["scene"] == scene and r["solver"] == "multigrid"]
            by = {}
            for r in mg:  # the bench's order: paper preset, converged default, then the scene's own
                key = r.get("preset", "")
                key = key if key in ("paper", "converged") and key not in by else "own"
                by.setdefault(key, r)
                error = max(100 * r["rel_position_error_motion"], 1e-5)
                points[key].append(f"{r['ms_per_frame']} {error} {scene}")
            if "paper" in by and "converged" in by:
                a, b = by["paper"], by["converged"]
                arrows.append((a["ms_per_frame"], max(100 * a["rel_position_error_motion"], 1e-5),
                               b["ms_per_frame"], max(100 * b["rel_position_error_motion"], 1e-5)))
        files = []
        for key, lines in points.items():
            if not lines:
                continue
            path = os.path.join(tmp, key + ".dat")
            with open(path, "w") as f:
                f.write("\n".join(lines) + "\n")
            files.append((key, path))
        styles = {"paper": "pt 6 ps 1.6 lc rgb '#c0392b'", "converged": "pt 7 ps 1.6 lc rgb '#1f77b4'",
                  "own": "pt 9 ps 1.4 lc rgb '#2ca02c'"}
        titles = {"paper": "paper preset (one linearized step)", "converged": "converged default",
                  "own": "scene's own setting"}
        plots = ", ".join(
            f"'{p}' using 1:2 with points {styles[k]} title \"{titles[k]}\", "
            f"'{p}' using 1:2:3 with labels offset 1.2,0.7 font ',8' notitle" for k, p in files)
        title = "Speed against error in motion: the paper preset and the converged default"
        script = gnuplot_header(out, "ms per frame (median, 2-core CPU)", title, arrows) + f"""
plot {plots}
"""
        subprocess.run(["gnuplot"], input=script, text=True, check=True)


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    rows = rows_of(sys.argv[2:])
    table(rows)
    plot(rows, sys.argv[1])


if __name__ == "__main__":
    main()
