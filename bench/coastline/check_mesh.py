#!/usr/bin/python3
"""Checks a coastal mesh (MSH 2.2 ASCII, as `meshctl -o x.msh22` writes it) against its region.

    check_mesh.py MESH.msh22 REGION.islands MIN_ISLAND_AREA_M2 [--area M2] [--request R.textproto]

prints one line of `key=value` pairs: nodes, triangles, q_min, q_mean (radius ratio
q = (b+c-a)(c+a-b)(a+b-c)/(abc), the formula of core/mesh/quality.h), valid, the boundary loops
(the outer ones and the holes) and islands=kept/total for the islands of REGION.islands (from
make_region.py) of at least MIN_ISLAND_AREA_M2; with --area, the mesh's area against it; with
--request (the region's request, as export_ocean.py writes it), on_land: the triangles whose
centroid lies on land, off the water the request's polygons bound (DistMesh keeps a triangle where
its centroid lies inside). Exits 1 when the mesh is invalid, an island of that size is lost or a
triangle lies on land.

Valid means what core/mesh/validity.h means: finite points, every triangle counter-clockwise
with positive area, every edge used once (boundary) or twice in opposite directions, every point
used. An island is kept when a point inside it lies in no triangle: the mesh has a hole there.
Needs only numpy, so that it runs wherever meshctl does.
"""
import argparse
import sys

import numpy as np

from request_polygons import on_land, polygons


def read_msh22(path):
    """Points #N by 2 and triangles #M by 3 (0-based) of an MSH 2.2 ASCII file."""
    with open(path) as fh:
        lines = fh.read().split("\n")
    i = lines.index("$Nodes")
    n = int(lines[i + 1])
    nodes = np.array([l.split() for l in lines[i + 2:i + 2 + n]], dtype=float)
    ids = nodes[:, 0].astype(np.int64)
    index = np.full(ids.max() + 1, -1, dtype=np.int64)
    index[ids] = np.arange(n)
    j = lines.index("$Elements")
    m = int(lines[j + 1])
    tris = []
    for l in lines[j + 2:j + 2 + m]:
        f = l.split()
        if f[1] == "2":  # a 3-node triangle: id type ntags tags... n1 n2 n3
            tris.append(f[-3:])
    return nodes[:, 1:3], index[np.array(tris, dtype=np.int64)]


def quality(p, t):
    a = np.linalg.norm(p[t[:, 1]] - p[t[:, 2]], axis=1)
    b = np.linalg.norm(p[t[:, 2]] - p[t[:, 0]], axis=1)
    c = np.linalg.norm(p[t[:, 0]] - p[t[:, 1]], axis=1)
    return (b + c - a) * (c + a - b) * (a + b - c) / (a * b * c)


def signed_areas(p, t):
    # About the first vertex, so that UTM northings do not cancel.
    u, v = p[t[:, 1]] - p[t[:, 0]], p[t[:, 2]] - p[t[:, 0]]
    return 0.5 * (u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0])


def validity(p, t):
    """The defects as text; empty when valid. Also returns the boundary edges (#B by 2)."""
    problems = []
    if not np.isfinite(p).all():
        problems.append("non-finite points")
    area = signed_areas(p, t)
    longest = np.max([np.sum((p[t[:, k]] - p[t[:, (k + 1) % 3]]) ** 2, axis=1) for k in range(3)],
                     axis=0)
    inverted = int(np.sum(2 * area <= 1e-12 * longest))
    if inverted:
        problems.append(f"{inverted} inverted or degenerate triangles")
    directed = np.concatenate([t[:, [0, 1]], t[:, [1, 2]], t[:, [2, 0]]])
    key = lambda e: e[:, 0] * len(p) + e[:, 1]
    d_keys, d_counts = np.unique(key(directed), return_counts=True)
    if (d_counts > 1).any():
        problems.append(f"{int(np.sum(d_counts > 1))} edges used twice in one direction")
    undirected = np.sort(directed, axis=1)
    u_keys, u_counts = np.unique(key(undirected), return_counts=True)
    if (u_counts > 2).any():
        problems.append(f"{int(np.sum(u_counts > 2))} edges used by 3+ triangles")
    unused = len(p) - len(np.unique(t))
    if unused:
        problems.append(f"{unused} unused points")
    once = np.isin(key(undirected), u_keys[u_counts == 1])
    return problems, directed[once], float(area.sum())


def boundary_loops(edges, n):
    """The boundary's closed loops as lists of vertex indices, following each edge's direction."""
    nxt = np.full(n, -1, dtype=np.int64)
    nxt[edges[:, 0]] = edges[:, 1]  # a vertex where two loops touch keeps one successor
    seen = np.zeros(n, dtype=bool)
    loops = []
    for start in edges[:, 0]:
        if seen[start]:
            continue
        loop, v = [], start
        while v >= 0 and not seen[v]:
            seen[v] = True
            loop.append(v)
            v = nxt[v]
        loops.append(loop)
    return loops


def covered(p, t, points):
    """Whether each of `points` (#K by 2) lies in a triangle: triangles are bucketed into grid
    cells by their bounding boxes, and each point is tested against its cell's triangles."""
    lo = p.min(axis=0)
    tmin, tmax = p[t].min(axis=1), p[t].max(axis=1)
    cell = np.median(tmax - tmin) * 2
    c0 = np.floor((tmin - lo) / cell).astype(np.int64)
    c1 = np.floor((tmax - lo) / cell).astype(np.int64)
    width = int(c1[:, 0].max()) + 2
    buckets = {}
    for k in range(len(t)):
        for cx in range(c0[k, 0], c1[k, 0] + 1):
            for cy in range(c0[k, 1], c1[k, 1] + 1):
                buckets.setdefault(cy * width + cx, []).append(k)
    result = np.zeros(len(points), dtype=bool)
    for i, q in enumerate(points):
        cx, cy = np.floor((q - lo) / cell).astype(np.int64)
        cand = np.array(buckets.get(int(cy) * width + int(cx), []), dtype=np.int64)
        if len(cand) == 0:
            continue
        a, b, c = p[t[cand, 0]], p[t[cand, 1]], p[t[cand, 2]]
        cross = lambda u, v, w: (v[:, 0] - u[:, 0]) * (w[:, 1] - u[:, 1]) - \
            (v[:, 1] - u[:, 1]) * (w[:, 0] - u[:, 0])
        qq = np.broadcast_to(q, a.shape)
        inside = (cross(a, b, qq) >= 0) & (cross(b, c, qq) >= 0) & (cross(c, a, qq) >= 0)
        result[i] = inside.any()
    return result


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("mesh")
    ap.add_argument("islands")
    ap.add_argument("min_island_area", type=float)
    ap.add_argument("--area", type=float, help="the domain's area, to compare the mesh's with")
    ap.add_argument("--request", help="the region's request, to find triangles on land")
    ap.add_argument("--orient", action="store_true",
                    help="turn clockwise triangles first (Gmsh orients each surface's triangles "
                         "as its boundary loops run; meshd's are all counter-clockwise)")
    a = ap.parse_args()

    p, t = read_msh22(a.mesh)
    if a.orient:
        t[signed_areas(p, t) < 0] = t[signed_areas(p, t) < 0][:, ::-1]
    q = quality(p, t)
    problems, boundary, area = validity(p, t)
    loops = boundary_loops(boundary, len(p))
    isl = np.loadtxt(a.islands, ndmin=2)
    big = isl[isl[:, 2] >= a.min_island_area] if len(isl) else isl
    lost = covered(p, t, big[:, :2]) if len(big) else np.zeros(0, dtype=bool)

    fields = [f"nodes={len(p)}", f"triangles={len(t)}", f"q_min={q.min():.3f}",
              f"q_mean={q.mean():.4f}", f"valid={'yes' if not problems else 'no'}",
              f"boundary_loops={len(loops)}",
              f"islands={int(len(big) - lost.sum())}/{len(big)}",
              f"islands_any_size={len(isl)}"]
    if a.area:
        fields.append(f"area_rel_err={(area - a.area) / a.area:+.4f}")
    land = np.zeros(len(t), dtype=bool)
    if a.request:
        land = on_land(polygons(a.request), p[t].mean(axis=1))
        fields.append(f"on_land={int(land.sum())}")
    print(" ".join(fields))
    for line in problems:
        print(f"check_mesh: invalid: {line}", file=sys.stderr)
    for x, y, s in big[lost]:
        print(f"check_mesh: island lost: ({x:.0f}, {y:.0f}), {s:.0f} m2", file=sys.stderr)
    for x, y in p[t[land]].mean(axis=1):
        print(f"check_mesh: triangle on land: centroid ({x:.1f}, {y:.1f})", file=sys.stderr)
    return 1 if problems or lost.any() or land.any() else 0


if __name__ == "__main__":
    sys.exit(main())
