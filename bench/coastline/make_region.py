#!/usr/bin/python3
"""Cuts a coastal region out of the GSHHG shorelines that Debian's GMT reads, as land polygons.

    bench/coastline/make_region.py --region 19.3/23.2/59.5/60.8 --resolution f OUT_PREFIX

writes OUT_PREFIX.geojson (one Polygon feature per piece of land, WGS 84 degrees),
OUT_PREFIX.env (shell variables for meshctl: TO_CRS, the UTM zone of the region's centre, and
CLIP, the largest UTM box inside the region less a margin, in metres) and OUT_PREFIX.islands
(a point inside each island and its area, in that CRS), and prints the counts.

GMT stores GSHHG in bins and `gmt coast -M -W` dumps the shorelines as pieces cut at the bins
and at the region's edge, not as polygons (GMT 6.4 cannot dump its filled polygons). So:
  1. dump the ocean shorelines (level 1) of the region;
  2. check that the pieces join up: a piece that leaves one bin starts again in the next at the
     same crossing point (exactly, once quantised to 1e-7 degree), so every end is shared by
     two pieces unless it lies on the region's edge;
  3. split the region's edge at those ends and polygonize pieces and edge together (GEOS)
     into faces that tile the region;
  4. ask GMT on which side each face lies (`gmt select -N`, a point inside each face), and
     keep the land faces.
The clip box stays a margin inside the region, so that the land cut at the region's edge
(step 3) is cut again by meshctl's --clip, and no edge of the dump reaches the mesh.

Needs gmt, a gmt-gshhg-* package of the resolution asked for, and python3-gdal.
"""
import argparse
import json
import math
import subprocess
import sys
import tempfile
from collections import defaultdict

from osgeo import ogr, osr

osr.UseExceptions()
ogr.UseExceptions()

QUANTUM = 1e-7  # degrees; GSHHG's own resolution is coarser than this


def gmt(args, **kw):
    """Runs GMT in a scratch directory, where it leaves its gmt.history."""
    with tempfile.TemporaryDirectory() as scratch:
        return subprocess.run(["gmt"] + args, check=True, capture_output=True, text=True,
                              cwd=scratch, **kw).stdout


def dump_shorelines(region, resolution):
    """Step 1: the level-1 shoreline pieces as lists of (lon, lat)."""
    out = gmt(["coast", f"-R{region}", f"-D{resolution}", "-M", "-W1/0.1p", "-A0/1/1"])
    pieces, piece = [], None
    for line in out.splitlines():
        if line.startswith(">"):
            piece = []
            pieces.append(piece)
        elif line.strip():
            lon, lat = map(float, line.split()[:2])
            piece.append((round(lon / QUANTUM) * QUANTUM, round(lat / QUANTUM) * QUANTUM))
    return [p for p in pieces if len(p) >= 2]


def on_edge(p, box):
    w, e, s, n = box
    return abs(p[0] - w) < QUANTUM or abs(p[0] - e) < QUANTUM or abs(p[1] - s) < QUANTUM or \
        abs(p[1] - n) < QUANTUM


def edge_segments(pieces, box):
    """Step 3's edge: the region's boundary, split at every piece end on it, as segments."""
    w, e, s, n = box
    # Position along the boundary, counter-clockwise from the south-west corner.
    def along(p):
        if abs(p[1] - s) < QUANTUM:
            return p[0] - w
        if abs(p[0] - e) < QUANTUM:
            return (e - w) + (p[1] - s)
        if abs(p[1] - n) < QUANTUM:
            return (e - w) + (n - s) + (e - p[0])
        return 2 * (e - w) + (n - s) + (n - p[1])
    stops = {(w, s), (e, s), (e, n), (w, n)}
    stops.update(end for p in pieces for end in (p[0], p[-1]) if on_edge(end, box))
    ring = sorted(stops, key=along)
    return [[ring[i], ring[(i + 1) % len(ring)]] for i in range(len(ring))]


def check_joined(pieces, box):
    """Step 2: the number of piece ends off the region's edge that no other piece shares."""
    degree = defaultdict(int)
    for p in pieces:
        if p[0] != p[-1]:
            degree[p[0]] += 1
            degree[p[-1]] += 1
    return sum(1 for q, d in degree.items() if d % 2 and not on_edge(q, box))


def polygonize(lines):
    """Step 3's faces. A few pieces touch or cross another inside (GSHHG's quantised bins), and
    GEOS polygonizes only noded lines: the union with one of their own points nodes them."""
    mls = ogr.Geometry(ogr.wkbMultiLineString)
    for line in lines:
        g = ogr.Geometry(ogr.wkbLineString)
        for lon, lat in line:
            g.AddPoint_2D(lon, lat)
        mls.AddGeometry(g)
    point = ogr.Geometry(ogr.wkbPoint)
    point.AddPoint_2D(*lines[0][0])
    faces = mls.Union(point).Polygonize()
    return [faces.GetGeometryRef(i).Clone() for i in range(faces.GetGeometryCount())]


def land_faces(faces, region, resolution):
    """Step 4: the faces whose inside point GMT finds on land (lakes and their islands count as
    land: only the ocean is water here)."""
    points = []
    for i, f in enumerate(faces):
        p = f.PointOnSurface()
        points.append(f"{p.GetX():.10f} {p.GetY():.10f} {i}")
    out = gmt(["select", f"-R{region}", f"-D{resolution}", "-Ns/k/k/k/k"],
              input="\n".join(points) + "\n")
    keep = {int(float(line.split()[2])) for line in out.splitlines() if line.strip()}
    return [f for i, f in enumerate(faces) if i in keep]


def from_wgs84(crs):
    """The transformation from WGS 84 degrees (longitude, latitude) to `crs`, x before y."""
    geo, target = osr.SpatialReference(), osr.SpatialReference()
    geo.ImportFromEPSG(4326)
    target.SetFromUserInput(crs)
    for ref in (geo, target):
        ref.SetAxisMappingStrategy(osr.OAMS_TRADITIONAL_GIS_ORDER)
    return osr.CoordinateTransformation(geo, target)


def utm_box(box, margin_m):
    """The UTM zone of the region's centre and the largest box in it inside the region, less
    margin_m on every side."""
    w, e, s, n = box
    zone = int(math.floor(((w + e) / 2 + 180) / 6)) % 60 + 1
    epsg = (32600 if s + n >= 0 else 32700) + zone
    to_utm = from_wgs84(f"EPSG:{epsg}")
    steps = [i / 100 for i in range(101)]
    side = lambda pts: [to_utm.TransformPoint(lon, lat)[:2] for lon, lat in pts]
    west = side([(w, s + t * (n - s)) for t in steps])
    east = side([(e, s + t * (n - s)) for t in steps])
    south = side([(w + t * (e - w), s) for t in steps])
    north = side([(w + t * (e - w), n) for t in steps])
    clip = (max(x for x, _ in west) + margin_m, max(y for _, y in south) + margin_m,
            min(x for x, _ in east) - margin_m, min(y for _, y in north) - margin_m)
    return f"EPSG:{epsg}", clip


def write_islands(land, crs, clip, path):
    """The islands (land wholly inside the clip box) in the UTM CRS, one line each: a point
    inside, and the area in square metres; what check_mesh.py looks for in the mesh."""
    to_utm = from_wgs84(crs)
    box = ogr.CreateGeometryFromWkt("POLYGON(({0} {1},{2} {1},{2} {3},{0} {3},{0} {1}))"
                                    .format(*clip))
    count = 0
    with open(path, "w") as fh:
        fh.write("# x y area_m2 of each island inside the clip box, in " + crs + "\n")
        for f in land:
            g = f.Clone()
            g.Transform(to_utm)
            if g.Within(box):
                p = g.PointOnSurface()
                fh.write(f"{p.GetX():.3f} {p.GetY():.3f} {g.GetArea():.1f}\n")
                count += 1
    return count


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--region", required=True, help="W/E/S/N in degrees")
    ap.add_argument("--resolution", default="f", help="GSHHG resolution: f, h, i, l or c")
    ap.add_argument("--margin", type=float, default=1000, help="metres between clip and region")
    ap.add_argument("out", help="output prefix: writes OUT.geojson and OUT.env")
    a = ap.parse_args()
    box = tuple(float(v) for v in a.region.split("/"))

    pieces = dump_shorelines(a.region, a.resolution)
    loose = check_joined(pieces, box)
    if loose:
        sys.exit(f"make_region: {loose} shoreline ends join no other piece; not polygons")
    faces = polygonize(pieces + edge_segments(pieces, box))
    land = land_faces(faces, a.region, a.resolution)
    if not land:
        sys.exit(f"make_region: no land in {a.region}")

    features = []
    for f in land:
        rings = [[list(f.GetGeometryRef(r).GetPoint_2D(k))
                  for k in range(f.GetGeometryRef(r).GetPointCount())]
                 for r in range(f.GetGeometryCount())]
        features.append({"type": "Feature", "properties": {},
                         "geometry": {"type": "Polygon", "coordinates": rings}})
    with open(a.out + ".geojson", "w") as fh:
        json.dump({"type": "FeatureCollection", "features": features}, fh)

    crs, clip = utm_box(box, a.margin)
    with open(a.out + ".env", "w") as fh:
        fh.write(f"# {a.region} at GSHHG resolution {a.resolution}\n")
        fh.write(f"TO_CRS={crs}\nCLIP={','.join(f'{v:.0f}' for v in clip)}\n")
    islands = write_islands(land, crs, clip, a.out + ".islands")
    vertices = sum(len(p) for p in pieces)
    print(f"make_region: {a.region} ({a.resolution}): {len(pieces)} shoreline pieces, "
          f"{vertices} vertices, {len(faces)} faces, {len(land)} land polygons ({islands} "
          f"islands inside the clip box) -> {a.out}.geojson; {crs}, "
          f"clip {clip[0]:.0f},{clip[1]:.0f},{clip[2]:.0f},{clip[3]:.0f}")


if __name__ == "__main__":
    main()
