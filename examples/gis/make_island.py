#!/usr/bin/env python3
"""Writes island.geojson: a made-up island in the open Atlantic (about 35 W, 40 N) with a crater
lake, and a feature of two islets, in longitude/latitude degrees (WGS 84). No real place: the
outlines are sums of a few sines, so that the file can be remade exactly and given away freely.

    make_island.py > island.geojson
"""

import json
import math

LON0, LAT0 = -35.0, 40.0
KM_PER_DEG_LAT = 111.0
KM_PER_DEG_LON = 111.32 * math.cos(math.radians(LAT0))


def ring(cx_km, cy_km, n, radius):
    """n points of radius(theta) km about (cx, cy) km, counter-clockwise, closed, in degrees."""
    points = []
    for k in range(n):
        t = 2 * math.pi * k / n
        r = radius(t)
        x, y = cx_km + r * math.cos(t), cy_km + r * math.sin(t)
        points.append([round(LON0 + x / KM_PER_DEG_LON, 6), round(LAT0 + y / KM_PER_DEG_LAT, 6)])
    return points + [points[0]]


def feature(fid, name, geometry):
    return {"type": "Feature", "id": fid, "properties": {"name": name}, "geometry": geometry}


main = ring(0, 0, 240, lambda t: 12 * (1 + 0.25 * math.sin(3 * t) + 0.1 * math.cos(5 * t)
                                       + 0.04 * math.sin(11 * t)) * (1 + 0.35 * math.cos(t) ** 2))
lake = ring(2, 1, 40, lambda t: 2.2 / math.sqrt(1 + 1.8 * math.sin(t) ** 2))[::-1]  # clockwise
islet_a = ring(33, -14, 60, lambda t: 3 * (1 + 0.2 * math.sin(4 * t)))
islet_b = ring(30, -24, 60, lambda t: 1.8 * (1 + 0.15 * math.cos(3 * t)))

collection = {
    "type": "FeatureCollection",
    "name": "island",
    "features": [
        feature(0, "Isla Grande", {"type": "Polygon", "coordinates": [main, lake]}),
        feature(1, "Islotes", {"type": "MultiPolygon",
                               "coordinates": [[islet_a], [islet_b]]}),
    ],
}
print(json.dumps(collection, separators=(",", ":")))
