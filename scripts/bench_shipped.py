#!/usr/bin/env python3
"""Every shipped scene and playback script run headless: frames, unconverged frames, warnings and
the median ms a frame (docs/benchmarks.md, "Every shipped scene and script").

  scripts/bench_shipped.py [--galsculpt PATH] [--only NAME[,NAME...]]

Runs `galsculpt run assets/scenes/S.json --frames N` for each scene and `galsculpt play
assets/scripts/P.json` for each script, one after the other, with the default thread count, and
writes docs/bench/shipped.json (with where and how it ran); `scripts/bench_page.py render` draws
the table from it. Warnings are the metrics' `warnings` column summed over the frames plus the
tools that acted on nothing (`idle_tools`). --only measures those names again and keeps the
others' rows.
"""
import csv
import json
import os
import statistics
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bench_page  # noqa: E402  (provenance: commit, machine, date)

ROOT = bench_page.ROOT
OUT = os.path.join(bench_page.BENCH, "shipped.json")
# Frames for each scene: enough to reach what it shows (Charpy's break, the armadillo's arm).
SCENE_FRAMES = {"armadillo": 60, "charpy": 80, "charpy_ductile": 80}
DEFAULT_FRAMES = 120


def measure(galsculpt, kind, name):
    folder = "scenes" if kind == "run" else "scripts"
    path = os.path.join(ROOT, "assets", folder, name + ".json")
    with tempfile.TemporaryDirectory() as out:
        command = [galsculpt, kind, path, "--out", out]
        if kind == "run":
            command += ["--frames", str(SCENE_FRAMES.get(name, DEFAULT_FRAMES))]
        subprocess.run(command, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        rows = list(csv.DictReader(open(os.path.join(out, "metrics.csv"))))
    return {
        "kind": kind,
        "name": name,
        "frames": len(rows),
        "unconverged_frames": sum(1 for r in rows if float(r["converged"]) == 0),
        "warnings": int(sum(float(r["warnings"]) + float(r["idle_tools"]) for r in rows)),
        "ms_per_frame": statistics.median(float(r["ms_total"]) for r in rows),
        "ms_p95": sorted(float(r["ms_total"]) for r in rows)[int(0.95 * (len(rows) - 1))],
    }


def main(argv):
    galsculpt = os.path.join(ROOT, "build", "app", "galsculpt")
    only = None
    if "--galsculpt" in argv:
        galsculpt = argv[argv.index("--galsculpt") + 1]
    if "--only" in argv:
        only = set(argv[argv.index("--only") + 1].split(","))
    kept = {}
    if only and os.path.exists(OUT):
        kept = {(r["kind"], r["name"]): r for r in json.load(open(OUT))["results"]}
    results = []
    for kind, folder in (("run", "scenes"), ("play", "scripts")):
        for file in sorted(os.listdir(os.path.join(ROOT, "assets", folder))):
            name = file[:-5]
            if only is not None and name not in only and (kind, name) in kept:
                results.append(kept[(kind, name)])
                continue
            print(f"bench_shipped: {kind} {name}", file=sys.stderr, flush=True)
            results.append(measure(galsculpt, kind, name))
    doc = {"results": results, "provenance": bench_page.provenance(
        "scripts/bench_shipped.py" + (" --only " + ",".join(sorted(only)) if only else ""))}
    os.makedirs(bench_page.BENCH, exist_ok=True)
    with open(OUT + ".tmp", "w") as f:
        json.dump(doc, f, indent=2)
        f.write("\n")
    os.replace(OUT + ".tmp", OUT)
    bench_page.render()


if __name__ == "__main__":
    main(sys.argv[1:])
