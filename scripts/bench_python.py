#!/usr/bin/env python3
"""Frames from Python against the command line: `galsculpt run SCENE --frames N` and
`Simulation(SCENE).step(N)` in their own processes, alternating, the medians of their wall
times (the scene's loading excluded: each side times only its frames, from the metrics'
ms_total for the command and around step() for Python).

  PYTHONPATH=build/python python3 scripts/bench_python.py build/app/galsculpt [SCENE] [--frames N] [--runs R]
"""
import argparse
import csv
import json
import pathlib
import statistics
import subprocess
import sys
import tempfile

PY_SIDE = """
import sys, time, galsculpt
sim = galsculpt.Simulation(sys.argv[1])
start = time.perf_counter()
sim.step(int(sys.argv[2]))
print(1000.0 * (time.perf_counter() - start))
"""


def cli_ms(binary, scene, frames):
    with tempfile.TemporaryDirectory() as out:
        subprocess.run([binary, "run", scene, "--frames", str(frames), "--out", out],
                       check=True, capture_output=True)
        with open(pathlib.Path(out) / "metrics.csv") as f:
            return sum(float(row["ms_total"]) for row in csv.DictReader(f))


def python_ms(scene, frames):
    r = subprocess.run([sys.executable, "-c", PY_SIDE, scene, str(frames)], check=True,
                       capture_output=True, text=True)
    return float(r.stdout.strip())


def main():
    p = argparse.ArgumentParser()
    p.add_argument("binary")
    p.add_argument("scene", nargs="?", default="assets/scenes/default.json")
    p.add_argument("--frames", type=int, default=100)
    p.add_argument("--runs", type=int, default=5)
    a = p.parse_args()
    cli, py = [], []
    for _ in range(a.runs):
        cli.append(cli_ms(a.binary, a.scene, a.frames))
        py.append(python_ms(a.scene, a.frames))
    row = {"scene": a.scene, "frames": a.frames, "runs": a.runs,
           "cli_ms_median": statistics.median(cli), "python_ms_median": statistics.median(py)}
    row["python_over_cli"] = row["python_ms_median"] / row["cli_ms_median"]
    print(json.dumps(row))


if __name__ == "__main__":
    main()
