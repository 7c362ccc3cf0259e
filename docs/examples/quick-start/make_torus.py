#!/usr/bin/env python3
"""Writes a closed torus as an OBJ: the quick start's stand-in for a mesh of your own.

  python3 make_torus.py OUT.obj [--major R] [--minor r] [--segments N]

The ring lies in the xz plane around the y axis, in metres (default: 8 cm across its centre line,
3.5 cm thick), its triangles wound outward.
"""
import argparse
import math

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("out")
parser.add_argument("--major", type=float, default=0.08, help="the ring's radius, m")
parser.add_argument("--minor", type=float, default=0.035, help="the tube's radius, m")
parser.add_argument("--segments", type=int, default=48, help="around the ring (the tube: half)")
args = parser.parse_args()

around, tube = args.segments, max(3, args.segments // 2)
with open(args.out, "w") as obj:
    for i in range(around):
        u = 2 * math.pi * i / around
        for j in range(tube):
            v = 2 * math.pi * j / tube
            r = args.major + args.minor * math.cos(v)
            obj.write(f"v {r * math.cos(u):.6f} {args.minor * math.sin(v):.6f} "
                      f"{r * math.sin(u):.6f}\n")
    for i in range(around):
        for j in range(tube):
            a = i * tube + j + 1
            b = ((i + 1) % around) * tube + j + 1
            c = ((i + 1) % around) * tube + (j + 1) % tube + 1
            d = i * tube + (j + 1) % tube + 1
            obj.write(f"f {a} {d} {c}\nf {a} {c} {b}\n")
