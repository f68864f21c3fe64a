#!/usr/bin/python3
"""How good a region's worst element can be: the sharp corners of its domain, and where a mesh's
poor triangles sit.

    corner_bound.py REQUEST.textproto [MESH.msh22]

A triangle that holds a corner of the domain with angle A (the boundary pins the corner's node)
has quality at most that of the isosceles triangle with apex angle A, q(A) = 8 sin(A/2)
sin^2((180 - A)/4): 0.59 at 20.8 degrees, 0.31 at 9.6. So no mesh that keeps a corner sharper
than 20.8 degrees reaches q_min 0.6, whatever the mesher. Reads the polygons of a request as
export_ocean.py writes it (a polygon directly under `subtract` is water inside its ring, any
other is land with water outside), prints how many corners of the water fall under a few angles
and the bound of the sharpest; with MESH, how many of its triangles under q 0.6 hold such a
corner, another polygon vertex, or none. Needs only numpy.
"""
import math
import sys

import numpy as np

from check_mesh import quality, read_msh22
from request_polygons import polygons

THRESHOLDS = (10.0, 15.0, 20.8, 30.0)
POOR = 0.6


def best_quality(angle):
    """The best q of a triangle with an angle of `angle` degrees: the isosceles one."""
    a = math.radians(angle)
    return 8 * math.sin(a / 2) * math.sin((math.pi - a) / 4) ** 2


def water_corners(rings):
    """{(x, y): the smallest angle of the water at that vertex, degrees}."""
    corners = {}
    for v, water_inside in rings:
        n = len(v)
        if n < 3:
            continue
        area = sum(v[i][0] * v[(i + 1) % n][1] - v[(i + 1) % n][0] * v[i][1] for i in range(n))
        for i in range(n):
            (ax, ay), (bx, by), (cx, cy) = v[i - 1], v[i], v[(i + 1) % n]
            ux, uy, wx, wy = ax - bx, ay - by, cx - bx, cy - by
            turn = math.degrees(math.atan2(ux * wy - uy * wx, ux * wx + uy * wy))
            inside = (-turn) % 360 if area > 0 else turn % 360  # the ring's interior angle
            angle = inside if water_inside else 360 - inside
            key = (round(bx, 1), round(by, 1))
            corners[key] = min(angle, corners.get(key, 360.0))
    return corners


def main():
    if len(sys.argv) not in (2, 3):
        sys.exit(__doc__.strip().split("\n\n")[1])
    corners = water_corners(polygons(sys.argv[1]))
    angles = sorted(corners.values())
    print(f"corner_bound: {len(corners)} polygon vertices; the sharpest corner of the water "
          f"{angles[0]:.1f} degrees, best q there {best_quality(angles[0]):.3f}")
    for t in THRESHOLDS:
        below = sum(1 for a in angles if a < t)
        print(f"  corners under {t:4.1f} degrees: {below:6d} (best q there under "
              f"{best_quality(t):.3f})")
    if len(sys.argv) == 2:
        return
    p, t = read_msh22(sys.argv[2])
    q = quality(p, t)
    poor = np.flatnonzero(q < POOR)
    sharp = other = 0
    for i in poor:
        held = [corners.get((round(p[k, 0], 1), round(p[k, 1], 1))) for k in t[i]]
        held = [a for a in held if a is not None]
        if held and min(held) < 20.8:
            sharp += 1
        elif held:
            other += 1
    print(f"  mesh: {len(t)} triangles, q_min {q.min():.3f}; {len(poor)} under {POOR}: {sharp} "
          f"at a corner under 20.8 degrees, {other} at another polygon vertex, "
          f"{len(poor) - sharp - other} away from the polygons' vertices")


if __name__ == "__main__":
    main()
