#!/usr/bin/env python3
"""Prints 'nodes tets q_min q_mean q<0.2 min_dihedral max_dihedral' for a tetrahedral mesh file
that meshio reads, with the measures of core/mesh3d/tet_quality.cuh (q = 3 r_in / R_circ)."""

import sys

import meshio
import numpy as np


def main(path):
    mesh = meshio.read(path)
    tets = np.concatenate([c.data for c in mesh.cells if c.type == "tetra"])
    used = np.unique(tets)
    p = mesh.points
    a, b, c, d = (p[tets[:, k]] for k in range(4))
    u, v, w = b - a, c - a, d - a
    six_volume = np.abs(np.einsum("ij,ij->i", u, np.cross(v, w)))
    area2 = sum(np.linalg.norm(np.cross(x, y), axis=1)
                for x, y in ((u, v), (v, w), (w, u), (c - b, d - b)))
    circum = (np.einsum("ij,ij->i", u, u)[:, None] * np.cross(v, w)
              + np.einsum("ij,ij->i", v, v)[:, None] * np.cross(w, u)
              + np.einsum("ij,ij->i", w, w)[:, None] * np.cross(u, v))
    q = 6 * six_volume ** 2 / (area2 * np.linalg.norm(circum, axis=1))
    # Dihedral angles: the inside angle between the outward normals of each pair of faces.
    corners = np.stack([a, b, c, d], axis=1)
    normals = []
    for k in range(4):
        q0, q1, q2 = (corners[:, (k + j) % 4] for j in (1, 2, 3))
        n = np.cross(q1 - q0, q2 - q0)
        inward = np.einsum("ij,ij->i", n, corners[:, k] - q0) > 0
        n[inward] *= -1
        normals.append(n / np.linalg.norm(n, axis=1)[:, None])
    angles = [180 - np.degrees(np.arccos(np.clip(np.einsum("ij,ij->i", normals[i], normals[j]),
                                                 -1, 1)))
              for i in range(4) for j in range(i + 1, 4)]
    angles = np.stack(angles, axis=1)
    print(len(used), len(tets), f"{q.min():.3f}", f"{q.mean():.4f}", int((q < 0.2).sum()),
          f"{angles.min():.1f}", f"{angles.max():.1f}")


if __name__ == "__main__":
    main(sys.argv[1])
