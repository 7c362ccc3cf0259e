#!/usr/bin/env python3
"""Speed against error from `galsculpt bench --json`: a PNG (gnuplot) and a Markdown table.

usage: scripts/plot-bench.py BENCH.json OUT.png [SCENE]
"""
import json
import os
import subprocess
import sys
import tempfile


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    doc = json.load(open(sys.argv[1]))
    scene = sys.argv[3] if len(sys.argv) > 3 else "sphere"
    rows = [r for r in doc["results"] if r.get("scene") == scene and "error" not in r]
    mg = [r for r in rows if r["solver"] == "multigrid"]
    ref = [r for r in rows if r["solver"] == "reference"]
    print("| grid | fine sweeps | coarse iters | ms/frame | fps | position error % | volume change % |")
    print("| --- | --- | --- | --- | --- | --- | --- |")
    for r in ref + sorted(mg, key=lambda r: (r["grid"], r["fine_sweeps"], r["coarse_iters"])):
        grid = r["grid"] or "reference"
        print(f"| {grid} | {r['fine_sweeps']} | {r['coarse_iters']} | {r['ms_per_frame']:.1f} | {r['fps']:.1f} | "
              f"{100 * r['rel_position_error']:.4f} | {r['volume_change_pct']:.4f} |")
    with tempfile.TemporaryDirectory() as tmp:
        files = []
        for grid in sorted({r["grid"] for r in mg}):
            path = os.path.join(tmp, grid.replace("/", "_") + ".dat")
            with open(path, "w") as f:
                for r in mg:
                    if r["grid"] == grid:
                        f.write(f"{r['ms_per_frame']} {max(100 * r['rel_position_error'], 1e-6)} "
                                f"{r['fine_sweeps']}/{r['coarse_iters']}\n")
            files.append((grid, path))
        plots = ", ".join(f"'{p}' using 1:2 with points pt 7 ps 1.2 title '{g}', "
                          f"'{p}' using 1:2:3 with labels offset 0.8,0.6 font ',7' notitle" for g, p in files)
        script = f"""
set terminal pngcairo size 900,600 font ',10'
set output '{sys.argv[2]}'
set logscale xy
set xlabel 'ms per frame (median)'
set ylabel 'position error vs reference (% of largest displacement)'
set title 'Galerkin multigrid on the {scene}: speed against error (labels: fine sweeps / coarse iterations)'
set grid
plot {plots}
"""
        subprocess.run(["gnuplot"], input=script, text=True, check=True)


if __name__ == "__main__":
    main()
