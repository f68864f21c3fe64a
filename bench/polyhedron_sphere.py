#!/usr/bin/env python3
"""The cost of a polyhedron's distance: the unit ball given as a closed triangle surface (a UV
sphere of about TRIANGLES triangles) against the analytic sphere, meshed through meshd at the
same h0, one Markdown row each: triangles, nodes, the job's own time, its relaxation and sliver
shares, the quality, the volume against the polyhedron's own.

    bench/polyhedron_sphere.py [--server HOST:PORT] [--h0 H0]
        [TRIANGLES ...]                  (default: 2000 20000 200000)

Needs a running meshd (e.g. build/bin/meshd --backend cpu) and the meshd package (README).
"""

import argparse
import time

import numpy as np

import meshd


def uv_sphere(triangles):
    """A UV sphere of radius 1 with about `triangles` triangles: rings of quads, polar fans."""
    rings = max(3, int(round(np.sqrt(triangles / 4))))
    segments = 2 * rings
    theta = np.pi * np.arange(1, rings) / rings
    phi = 2 * np.pi * np.arange(segments) / segments
    t, p = np.meshgrid(theta, phi, indexing="ij")
    body = np.stack([np.sin(t) * np.cos(p), np.sin(t) * np.sin(p), np.cos(t)], -1).reshape(-1, 3)
    vertices = np.vstack([[0, 0, 1], body, [0, 0, -1]])
    ring = lambda i, j: 1 + (i - 1) * segments + (j % segments)  # noqa: E731
    j = np.arange(segments)
    tris = [np.stack([np.zeros(segments, int), ring(1, j), ring(1, j + 1)], 1)]
    for i in range(1, rings - 1):
        a, b, c, d = ring(i, j), ring(i + 1, j), ring(i + 1, j + 1), ring(i, j + 1)
        tris += [np.stack([a, b, c], 1), np.stack([a, c, d], 1)]
    south = len(vertices) - 1
    tris.append(np.stack([np.full(segments, south), ring(rings - 1, j + 1), ring(rings - 1, j)], 1))
    return vertices, np.vstack(tris)


def enclosed_volume(v, t):
    return np.einsum("ij,ij->i", v[t[:, 0]], np.cross(v[t[:, 1]], v[t[:, 2]])).sum() / 6


def row(client, label, solid, h0, triangles, exact):
    start = time.monotonic()
    mesh = client.generate(meshd.request(solid, h0=h0))
    wall = time.monotonic() - start
    s, q = mesh.stats, mesh.quality
    print(f"| {label} | {triangles} | {len(mesh.points)} | {s.t_mesh:.2f} | {wall:.2f} "
          f"| {s.t_slivers:.2f} | {q.q_min:.3f} | {q.q_mean:.4f} | {q.min_dihedral_deg:.1f} "
          f"| {100 * (q.volume - exact) / exact:+.2f}% | {q.max_surface_offset / h0:.1e} |")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("triangles", nargs="*", type=int, default=[2000, 20000, 200000])
    parser.add_argument("--server", default="127.0.0.1:50051")
    parser.add_argument("--h0", type=float, default=0.087)
    args = parser.parse_args()
    client = meshd.Client(args.server)
    print("| solid | triangles | nodes | t_mesh s | wall s | t_slivers s | q_min | q_mean "
          "| min dihedral | volume vs its own | surface off / h0 |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    row(client, "sphere", meshd.sphere(1.0), args.h0, "", 4 / 3 * np.pi)
    for n in args.triangles:
        v, t = uv_sphere(n)
        row(client, "polyhedron", meshd.polyhedron(v, t), args.h0, len(t), enclosed_volume(v, t))


if __name__ == "__main__":
    main()
