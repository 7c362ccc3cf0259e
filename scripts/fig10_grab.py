#!/usr/bin/env python3
"""The paper's Fig. 10 as a validation: a limb of the human figure grabbed through the physics
and by a purely geometric grab, and the local volume change of the grabbed region for both.

  PYTHONPATH=build/python python3 scripts/fig10_grab.py OUT [--frames 60] [--lift 0.2]

The physics grab is the app's: a `brush` event on the scene (assets/scenes/human.json) that holds
the vertices within the radius of a point on the right hand and moves them together by the
offset over half the frames, then holds them there while the rest of the run settles. The
geometric grab is Blender's: every rest position within the radius moves by w(d) times the
offset, w = (1 - (d/R)^2)^2 (the same falloff the shaping brushes use), nothing else moves.
Gravity is off (a copy of the scene in OUT): the soft flesh figure sags and sways under its own
weight by more than the grab moves the hand, and Fig. 10 is about the grab. The region is the elements
whose centroid lies within twice the radius of the grab's centre at rest. Writes the surfaces
(OBJ; the geometric one as a TetGen mesh as well) and renders them with `galsculpt render`, and
prints a Markdown table. Uses the Python module: nothing of the physics is reimplemented here.
"""
import argparse
import json
import os
import shutil
import subprocess
import sys

import numpy as np

import galsculpt

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCENE = os.path.join(ROOT, "assets", "scenes", "human.json")


def signed_volumes(x, tets):
    a, b, c, d = (x[tets[:, k]] for k in range(4))
    return np.einsum("ij,ij->i", b - a, np.cross(c - a, d - a)) / 6.0


def region_change(x, rest, tets, region):
    v0 = signed_volumes(rest, tets)[region]
    v = signed_volumes(x, tets)[region]
    return 100.0 * (v.sum() / v0.sum() - 1.0), 100.0 * np.abs(v / v0 - 1.0).max(), int((v <= 0).sum())


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("out")
    ap.add_argument("--frames", type=int, default=60)
    ap.add_argument("--lift", type=float, default=0.2, help="the grab's upward offset (m)")
    ap.add_argument("--radius", type=float, default=0.07)
    ap.add_argument("--binary", default=os.path.join(ROOT, "build", "app", "galsculpt"))
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    scene = json.load(open(SCENE))
    scene["gravity"] = [0, 0, 0]
    scene_file = os.path.join(a.out, "human_no_gravity.json")
    with open(scene_file, "w") as f:
        json.dump(scene, f, indent=1)

    still = galsculpt.Simulation(scene_file)
    rest = still.rest_positions.copy()
    tets = still.tets.copy()
    hand = rest[np.argmax(rest[:, 0])]  # the tip of the right hand
    centre = hand - np.array([0.03, 0.0, 0.0])
    offset = np.array([0.0, a.lift, 0.0])
    centroids = rest[tets].mean(axis=1)
    region = np.linalg.norm(centroids - centre, axis=1) < 2.0 * a.radius

    # Physics: the app's grab, then held while the figure settles.
    sim = galsculpt.Simulation(scene_file)
    sim.apply({"frame": 0, "tool": "brush", "center": centre.tolist(), "radius": a.radius,
               "offset": offset.tolist(), "duration": a.frames // 2, "hold": True})
    report = sim.step(a.frames)
    physics = sim.positions.copy()
    sim.export(os.path.join(a.out, "physics.obj"))

    # Geometric: the falloff applied to the rest positions.
    d = np.linalg.norm(rest - centre, axis=1)
    w = np.where(d < a.radius, (1.0 - (d / a.radius) ** 2) ** 2, 0.0)
    geometric = rest + w[:, None] * offset[None, :]
    stem = os.path.join(a.out, "geometric")
    for ext in (".node", ".ele", ".face", ".damage", ".vtk"):
        if os.path.exists(stem + ext):
            os.remove(stem + ext)
    with open(stem + ".node", "w") as f:
        f.write(f"{len(geometric)} 3 0 0\n")
        for i, p in enumerate(geometric):
            f.write(f"{i} {p[0]!r} {p[1]!r} {p[2]!r}\n")
    with open(stem + ".ele", "w") as f:
        f.write(f"{len(tets)} 4 0\n")
        for i, t in enumerate(tets):
            f.write(f"{i} {t[0]} {t[1]} {t[2]} {t[3]}\n")

    rows = []
    for name, x in (("physics grab (converged)", physics), ("geometric grab (falloff)", geometric)):
        total, worst, inverted = region_change(x, rest, tets, region)
        moved = np.linalg.norm(x - rest, axis=1).max()
        rows.append((name, total, worst, inverted, moved))
    print(f"Human figure ({len(rest)} vertices, {len(tets)} tets), right hand grabbed at "
          f"{np.round(centre, 3).tolist()}, radius {a.radius} m, lifted {a.lift} m; region: "
          f"{int(region.sum())} elements within {2 * a.radius} m; physics: {a.frames} frames, the "
          f"last one {'converged' if report['converged'] else 'NOT converged'} "
          f"(residual {report['residual']:.2g})\n")
    print("| grab | region volume change % | largest element volume change % | elements inside out | largest motion (m) |")
    print("| --- | --- | --- | --- | --- |")
    for name, total, worst, inverted, moved in rows:
        print(f"| {name} | {total:+.2f} | {worst:.1f} | {inverted} | {moved:.3f} |")

    for name in ("physics.obj", "geometric.node"):
        views = os.path.join(a.out, name.split(".")[0])
        subprocess.run([a.binary, "render", os.path.join(a.out, name), "--out", views,
                        "--size", "400x400"], check=True, capture_output=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
