#!/usr/bin/env python3
"""Writes the requests of the many-primitives benchmark (bench/RESULTS.md) as text protos.

  many_primitives.py OUTDIR

holes_N.textproto   the square [0, 10]^2 minus N disks on a jittered grid (N = 10 ... 10,000),
                    the sizes of issue-style CSG trees of many shapes;
disks_N.textproto   a union of N small disks (N = 1,000 and 10,000), an archipelago;
ragged_V.textproto  the square minus a lake whose shoreline is one polygon of V vertices
                    (V = 1,000 ... 1,000,000), a wavy closed curve; auto_corners off, since
                    every vertex of a finely sampled curve would otherwise be pinned.
Meshed at equal node count (meshbench --nodes), the per-iteration times show what a tree of
many primitives, or a long polygon, costs over a small one. Same seed, same files.
"""
import math
import os
import random
import sys


def disk(x, y, r):
    return f"circle {{ center {{ x: {x:.9g} y: {y:.9g} }} radius: {r:.9g} }}"


def jittered_grid(n, rng, size=10.0):
    side = math.ceil(math.sqrt(n))
    cell = size / side
    out = []
    for k in range(n):
        i, j = k % side, k // side
        out.append(((i + 0.5 + rng.uniform(-0.2, 0.2)) * cell,
                    (j + 0.5 + rng.uniform(-0.2, 0.2)) * cell, 0.25 * cell))
    return out


def square():
    return "rectangle { min { x: 0 y: 0 } max { x: 10 y: 10 } }"


def write(path, geometry, comment, corners=True):
    with open(path, "w") as f:
        f.write("# proto-file: meshd/v1/request.proto\n# proto-message: meshd.v1.MeshRequest\n")
        f.write(f"# {comment} Written by bench/many_primitives.py.\n")
        f.write(f"geometry {{ {geometry} }}\nh0: 0.1\nauto_corners: {str(corners).lower()}\n")


def main():
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    rng = random.Random(17)
    for n in (10, 100, 1000, 10000):
        holes = " ".join(f"subtract {{ name: \"hole\" {disk(*d)} }}" for d in jittered_grid(n, rng))
        write(os.path.join(out, f"holes_{n}.textproto"),
              f"difference {{ base {{ name: \"outer\" {square()} }} {holes} }}",
              f"The square minus {n} disks.")
    for n in (1000, 10000):
        disks = " ".join(f"shapes {{ {disk(x, y, 1.6 * r)} }}" for x, y, r in jittered_grid(n, rng))
        write(os.path.join(out, f"disks_{n}.textproto"), f"union {{ {disks} }}",
              f"A union of {n} disks.")
    for v in (1000, 10000, 100000, 1000000):
        pts = []
        for k in range(v):
            a = 2 * math.pi * k / v
            r = 3.0 * (1 + 0.3 * math.sin(7 * a) + 0.03 * math.sin(97 * a))
            pts.append(f"vertices {{ x: {5 + r * math.cos(a):.12g} y: {5 + r * math.sin(a):.12g} }}")
        lake = f"polygon {{ {' '.join(pts)} }}"
        write(os.path.join(out, f"ragged_{v}.textproto"),
              f"difference {{ base {{ name: \"outer\" {square()} }} subtract {{ name: \"shore\" {lake} }} }}",
              f"The square minus a smooth lake of {v} vertices (its vertices are no corners).",
              corners=False)


if __name__ == "__main__":
    main()
