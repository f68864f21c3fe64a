"""The polygons of a coastal request (export_ocean.py's textproto), and which points lie on land.

A polygon directly under `subtract` is water inside its ring (a lake), any other is land with
water outside. The rings nest (islands in lakes in land), so a point lies on land exactly when an
odd number of rings enclose it. Needs only numpy.
"""
import re

import numpy as np


def polygons(path):
    """[(vertices, water_inside)] of every polygon of a request's geometry (written as text); the
    size field's copies (a distance to the land) are left out."""
    text = "\n".join(l for l in open(path) if not l.lstrip().startswith("#"))
    stack, found, ring, x = [], [], None, 0.0
    for tok in re.findall(r"[A-Za-z_]+\s*\{|\}|[xy]:\s*[-+\d.eE]+", text):
        if tok.endswith("{"):
            stack.append(tok[:-1].strip())
            if stack[-1] == "polygon" and stack[0] == "geometry":
                ring = ([], len(stack) > 1 and stack[-2] == "subtract")
        elif tok == "}":
            if stack.pop() == "polygon" and ring is not None:
                found.append(ring)
                ring = None
        elif tok[0] == "x":
            x = float(tok[2:])
        elif ring is not None and stack and stack[-1] == "vertices":
            ring[0].append((x, float(tok[2:])))
    return found


def on_land(rings, points, row_height=200.0, chunk=1024):
    """Whether each of `points` (#K by 2) lies inside an odd number of `rings`: a ray to +x
    crosses their edges an odd number of times. Edges and points are bucketed into rows of
    `row_height`, so that each point meets only the edges of its row."""
    rings = [v for v, _ in rings if len(v) >= 3]
    if not rings or len(points) == 0:
        return np.zeros(len(points), dtype=bool)
    a = np.concatenate([np.asarray(v, dtype=float) for v in rings])
    b = np.concatenate([np.roll(np.asarray(v, dtype=float), -1, axis=0) for v in rings])
    lo = float(min(a[:, 1].min(), points[:, 1].min()))
    first = np.floor((np.minimum(a[:, 1], b[:, 1]) - lo) / row_height).astype(np.int64)
    last = np.floor((np.maximum(a[:, 1], b[:, 1]) - lo) / row_height).astype(np.int64)
    row = np.floor((points[:, 1] - lo) / row_height).astype(np.int64)
    result = np.zeros(len(points), dtype=bool)
    order = np.argsort(first)
    first, last, a, b = first[order], last[order], a[order], b[order]
    for r in np.unique(row):
        edges = np.flatnonzero(last[:np.searchsorted(first, r, side="right")] >= r)
        ea, eb = a[edges], b[edges]
        here = np.flatnonzero(row == r)
        for s in range(0, len(here), chunk):
            q = points[here[s:s + chunk]]
            qx, qy = q[:, :1], q[:, 1:2]
            straddles = (ea[:, 1] > qy) != (eb[:, 1] > qy)
            with np.errstate(divide="ignore", invalid="ignore"):
                x = ea[:, 0] + (qy - ea[:, 1]) * (eb[:, 0] - ea[:, 0]) / (eb[:, 1] - ea[:, 1])
            result[here[s:s + chunk]] = (np.sum(straddles & (x > qx), axis=1) % 2) == 1
    return result
