#!/usr/bin/env python3
"""Draws docs/images/surface_construction.png: the corner-cell construction of the
visualization surface (docs/surface.md), in its 2D analogue (triangles instead of tets).

Usage: scripts/plot-surface-figure.py OUT.png   (needs gnuplot with the pngcairo terminal)
"""
import math
import subprocess
import sys

# A patch of a triangular lattice.
N = 5
verts = []
for j in range(N):
    for i in range(N):
        verts.append((i + 0.5 * j, j * math.sqrt(3) / 2))
def vid(i, j):
    return j * N + i
tris = []
for j in range(N - 1):
    for i in range(N - 1):
        tris.append((vid(i, j), vid(i + 1, j), vid(i, j + 1)))
        tris.append((vid(i + 1, j), vid(i + 1, j + 1), vid(i, j + 1)))

def key(a, b):
    return (min(a, b), max(a, b))

edge_tris = {}
for t, tri in enumerate(tris):
    for k in range(3):
        edge_tris.setdefault(key(tri[k], tri[(k + 1) % 3]), []).append(t)
boundary = [e for e, ts in edge_tris.items() if len(ts) == 1]

# Damaged edges: the edges crossed by a cut from the left boundary to the middle (a slit).
def crosses(e, p, q):
    a, b = verts[e[0]], verts[e[1]]
    def orient(u, v, w):
        return (v[0] - u[0]) * (w[1] - u[1]) - (v[1] - u[1]) * (w[0] - u[0])
    return (orient(p, q, a) * orient(p, q, b) < 0) and (orient(a, b, p) * orient(a, b, q) < 0)
cut_from, cut_to = (-0.5, 1.5), (3.1, 1.62)
damaged = {e for e in edge_tris if crosses(e, cut_from, cut_to)}

mid = lambda e: tuple((verts[e[0]][k] + verts[e[1]][k]) / 2 for k in range(2))
cen = lambda t: tuple(sum(verts[v][k] for v in tris[t]) / 3 for k in range(2))

def groups(t):
    """Corners of triangle t joined by undamaged edges (union-find on three)."""
    tri = tris[t]
    label = {v: v for v in tri}
    for _ in range(3):
        for k in range(3):
            a, b = tri[k], tri[(k + 1) % 3]
            if key(a, b) not in damaged:
                m = min(label[a], label[b])
                label[a] = label[b] = m
    return label

def toward(p, v, d=0.07):
    target = verts[v] if isinstance(v, int) else v
    dx, dy = target[0] - p[0], target[1] - p[1]
    n = math.hypot(dx, dy)
    return (p[0] + d * dx / n, p[1] + d * dy / n)

lines = {"mesh": [], "cells": [], "outer": [], "sideA": [], "sideB": [], "damaged": []}
for e in edge_tris:
    lines["mesh"].append((verts[e[0]], verts[e[1]]))
for t, tri in enumerate(tris):
    for k in range(3):
        lines["cells"].append((mid(key(tri[k], tri[(k + 1) % 3])), cen(t)))
for e in damaged:
    lines["damaged"].append((verts[e[0]], verts[e[1]]))
for e in boundary:
    a, b = e
    if e in damaged:  # the boundary splits at the midpoint: each side keeps its half
        lines["outer"].append((verts[a], toward(mid(e), a)))
        lines["outer"].append((toward(mid(e), b), verts[b]))
    else:
        lines["outer"].append((verts[a], verts[b]))
# Crack faces: for every damaged edge of every triangle, midpoint-to-centroid, once per side.
for e in damaged:
    for t in edge_tris[e]:
        g = groups(t)
        for side, name in ((e[0], "sideA"), (e[1], "sideB")):
            m = toward(mid(e), side)
            c = cen(t)
            split = len(set(g.values())) > 1
            if split:  # this side's copy of the centroid, nudged towards its own corners
                mine = [v for v in tris[t] if g[v] == g[side]]
                c = toward(c, tuple(sum(verts[v][k] for v in mine) / len(mine) for k in range(2)))
            lines[name].append((m, c))

def block(segs):
    return "\n".join(f"{a[0]} {a[1]}\n{b[0]} {b[1]}\n" for a, b in segs) + "e\n"

out = sys.argv[1] if len(sys.argv) > 1 else "surface_construction.png"
script = f"""set terminal pngcairo size 1000,760 font 'DejaVu Sans,13'
set output '{out}'
set size ratio -1
unset border; unset tics; unset key
set title 'Corner cells (dashed) and the surface of a partial cut (2D analogue)'
plot '-' with lines lc rgb '#c8c8c8' lw 1, \\
     '-' with lines lc rgb '#909090' dt 2 lw 1, \\
     '-' with lines lc rgb '#e07070' lw 2, \\
     '-' with lines lc rgb '#202020' lw 3, \\
     '-' with lines lc rgb '#1f5fbf' lw 3, \\
     '-' with lines lc rgb '#2a9d3a' lw 3
""" + block(lines["mesh"]) + block(lines["cells"]) + block(lines["damaged"]) + \
    block(lines["outer"]) + block(lines["sideA"]) + block(lines["sideB"])
subprocess.run(["gnuplot"], input=script.encode(), check=True)
print("wrote", out)
