#!/usr/bin/python3
"""The sea of a region as meshctl would mesh it, written as a meshd request and a Gmsh .geo.

    export_ocean.py REGION.geojson --to-crs EPSG:32634 --clip X0,Y0,X1,Y1 --h0 H \
        --simplify F --grade H_MIN,SLOPE,H_MAX OUT_PREFIX

`meshctl generate --import REGION.geojson --to-crs .. --clip .. --subtract-from-clip
--simplify F --h0 H --grade ..` sends the clip box minus the land, each land polygon reprojected,
clipped, simplified and filtered as client/gis_import.cpp does it. This script takes the same
steps with the same GDAL/GEOS calls, so that meshbench (engine time alone, and runs on a machine
with no GDAL) and Gmsh get the same polygons:
  OUT.textproto  the request: difference(clip box, union(land polygons)), the --grade size term
                 about the land, h0; with --feature K,H_MIN,H_MAX a feature-size term too (K
                 elements across channels) and with --gradation G the field's gradation, as
                 meshctl's flags of those names add them;
  OUT.geo        the same sea for Gmsh (box minus the union of the land, by GEOS), its size
                 field Threshold(Distance to the shoreline), i.e. hs * h0 * min(H_MAX, H_MIN +
                 SLOPE d), where `gmsh -setnumber hs S` scales it (default 1) and
                 `-setnumber algo A` picks the 2D algorithm (default 6, Frontal-Delaunay).
                 Gmsh has no feature-size or gradation field of its own: its field stays the
                 distance term, and run.sh matches the node counts.
Prints the polygon and vertex counts, which meshctl's own summary line must match.

--open F goes one step beyond meshctl: water narrower than F * h0 is closed before the
simplification (opened_land), because a mesh cannot resolve it and its acute corners would set
the worst elements; the simplification's own acute corners are rounded by a second, smaller
opening after it. With it the request is no longer what meshctl --import sends, but meshd and
Gmsh still get the same polygons.
"""
import argparse
import sys

from osgeo import ogr, osr

ogr.UseExceptions()
osr.UseExceptions()


def ring_vertices(ring, min_area):
    """gis_import.cpp's ring_vertices: no closing or repeated vertex; None when degenerate."""
    v = []
    for i in range(ring.GetPointCount()):
        p = ring.GetPoint_2D(i)
        if not v or p != v[-1]:
            v.append(p)
    while len(v) > 1 and v[-1] == v[0]:
        v.pop()
    if len(v) < 3:
        return None
    x0, y0 = v[0]
    twice = sum((v[i][0] - x0) * (v[i + 1][1] - y0) - (v[i][1] - y0) * (v[i + 1][0] - x0)
                for i in range(1, len(v) - 1))
    xs, ys = [p[0] for p in v], [p[1] for p in v]
    span = max(max(xs) - min(xs), max(ys) - min(ys))
    if not abs(twice) > max(1e-12 * span * span, 2 * min_area):
        return None
    return v


def polygons_of(g):
    """The polygonal parts of a geometry (what an intersection leaves may hold lines)."""
    t = ogr.GT_Flatten(g.GetGeometryType())
    if g.IsEmpty():
        return []
    if t == ogr.wkbPolygon:
        return [g]
    if t in (ogr.wkbMultiPolygon, ogr.wkbGeometryCollection):
        return [p for i in range(g.GetGeometryCount()) for p in polygons_of(g.GetGeometryRef(i))]
    return []


def rings_of(g, tolerance):
    """Step 6: (outer, [holes]) vertex lists of each polygon of g, degenerate rings left out."""
    land = []
    for poly in polygons_of(g):
        outer = ring_vertices(poly.GetGeometryRef(0), tolerance ** 2)
        if outer is None:
            continue
        holes = [ring_vertices(poly.GetGeometryRef(i), tolerance ** 2)
                 for i in range(1, poly.GetGeometryCount())]
        land.append((outer, [h for h in holes if h is not None]))
    return land


def box_polygon(clip):
    return ogr.CreateGeometryFromWkt("POLYGON(({0} {1},{2} {1},{2} {3},{0} {3},{0} {1}))"
                                     .format(*clip))


def opened_land(features, clip, radius, tolerance, min_pocket=0.0):
    """The land once the sea is opened by `radius` (eroded, then dilated): water narrower than
    2 radius (channels, inlets, the slivers where a coast meets the clip box at a grazing angle)
    becomes land, and every acute corner of the sea is rounded to that radius. Arcs get 30
    segments a quarter circle, 3 degrees a vertex: under the 5 degrees at which meshd pins a
    polygon vertex. Then simplified as a whole, so that neighbouring pieces keep their topology,
    and opened again by half the radius: the simplification cuts across the arcs and makes acute
    corners of its own (down to 2 degrees where a coast meets the clip box at a grazing angle),
    which the second opening rounds; its arcs stay as they are. Last, with min_pocket > 0, the
    pockets of sea under min_pocket m2 (lakes, and water the openings cut off from the rest)
    become land, as islands under the resolution may be lost: a pocket a few edges across meshes
    into a handful of poor triangles, and the triangles of one next to the sea straddle the land
    between them."""
    union = ogr.Geometry(ogr.wkbMultiPolygon)
    for g in features:
        for poly in polygons_of(g):
            union.AddGeometry(poly)
    box = box_polygon(clip)
    opened = lambda land, r: box.Difference(box.Difference(land).Buffer(-r, 30).Buffer(r, 30))
    land = opened(union.UnionCascaded(), radius)
    if tolerance > 0:
        land = opened(land.SimplifyPreserveTopology(tolerance), radius / 2)
    if min_pocket > 0:
        land = filled_pockets(land, box, min_pocket)
    return rings_of(land, tolerance)


def filled_pockets(land, box, min_area):
    """land with every part of the sea (box minus land) of area under min_area added to it."""
    sea = box.Difference(land)  # kept alive: polygons_of returns references into it
    pockets = ogr.Geometry(ogr.wkbMultiPolygon)
    for p in polygons_of(sea):
        if p.GetArea() < min_area:
            pockets.AddGeometry(p)
    return land.Union(pockets) if pockets.GetGeometryCount() else land


def import_land(path, to_crs, clip, tolerance, open_radius=0, min_pocket=0):
    """Steps 3-6 of gis_import.h for every feature: list of (outer, [holes]) vertex lists; with
    open_radius > 0, opened_land of the clipped features instead of step 5 per feature."""
    ds = ogr.Open(path)
    layer = ds.GetLayer(0)
    target = osr.SpatialReference()
    target.SetFromUserInput(to_crs)
    source = layer.GetSpatialRef()
    for ref in (source, target):
        ref.SetAxisMappingStrategy(osr.OAMS_TRADITIONAL_GIS_ORDER)
    transform = osr.CoordinateTransformation(source, target)
    box = box_polygon(clip)
    clipped = []
    for feature in layer:
        g = feature.GetGeometryRef().Clone()
        g.Transform(transform)
        clipped.append(g.Intersection(box))
    if open_radius > 0:
        return opened_land(clipped, clip, open_radius, tolerance, min_pocket)
    land = []
    for g in clipped:
        if tolerance > 0 and not g.IsEmpty():
            g = g.SimplifyPreserveTopology(tolerance)
        land.extend(rings_of(g, tolerance))
    return land


def shape_text(outer, holes):
    poly = lambda ring: "polygon { " + " ".join(
        f"vertices {{ x: {x:.17g} y: {y:.17g} }}" for x, y in ring) + " }"
    if not holes:
        return "{ " + poly(outer) + " }"
    return "{ difference { base { " + poly(outer) + " } " + " ".join(
        "subtract { " + poly(h) + " }" for h in holes) + " } }"


def write_request(path, land, clip, h0, grade, feature, gradation):
    # As client/imported_shape.cpp builds it: a lone polygon stands alone, more form a union.
    if len(land) == 1:
        shape = shape_text(*land[0])[2:-2]
    else:
        shape = "union { " + " ".join("shapes " + shape_text(o, h) for o, h in land) + " }"
    land_shape = f'name: "land" {shape}'
    with open(path, "w") as fh:
        fh.write("# proto-file: meshd/v1/request.proto\n# proto-message: meshd.v1.MeshRequest\n")
        fh.write("# Written by bench/coastline/export_ocean.py: the clip box minus the land.\n")
        fh.write(f'geometry {{ difference {{ base {{ name: "clip" rectangle {{ min {{ x: {clip[0]} '
                 f'y: {clip[1]} }} max {{ x: {clip[2]} y: {clip[3]} }} }} }}\n')
        fh.write(f"  subtract {{ {land_shape} }} }} }}\n")
        fh.write(f"size {{ terms {{ distance {{ shape {{ {land_shape} }}\n")
        fh.write(f"  h_min: {grade[0]} slope: {grade[1]} h_max: {grade[2]} }} }}\n")
        if feature:
            fh.write(f"  terms {{ feature {{ elements: {feature[0]} h_min: {feature[1]} "
                     f"h_max: {feature[2]} }} }}\n")
        if gradation:
            fh.write(f"  gradation: {gradation}\n")
        fh.write("}\n")
        fh.write(f"h0: {h0}\n")


def write_geo(path, land, clip, h0, grade):
    """The sea as GEOS computes it (box minus the union of the land), for Gmsh's built-in
    kernel: one point per vertex, one line per edge, shoreline lines first so that the
    distance field lists them as one range."""
    box = box_polygon(clip)
    union = ogr.Geometry(ogr.wkbMultiPolygon)
    for outer, holes in land:
        p = ogr.Geometry(ogr.wkbPolygon)
        for ring in [outer] + holes:
            r = ogr.Geometry(ogr.wkbLinearRing)
            for x, y in ring + [ring[0]]:
                r.AddPoint_2D(x, y)
            p.AddGeometry(r)
        union.AddGeometry(p)
    sea = box.Difference(union.UnionCascaded())
    on_box = lambda a, b: (a[0] == b[0] and a[0] in (clip[0], clip[2])) or \
        (a[1] == b[1] and a[1] in (clip[1], clip[3]))
    # Rings of the sea may touch at a vertex (two islands meeting at a point): one Gmsh point
    # there, or Gmsh cannot recover the boundary.
    points, index, shore, edge, surfaces = [], {}, [], [], []
    for poly in polygons_of(sea):
        loops = []
        for i in range(poly.GetGeometryCount()):
            ring = ring_vertices(poly.GetGeometryRef(i), 0)
            ids = []
            for p in ring:
                if p not in index:
                    index[p] = len(points)
                    points.append(p)
                ids.append(index[p])
            loop = []
            for k in range(len(ring)):
                a, b = ids[k], ids[(k + 1) % len(ring)]
                (edge if on_box(points[a], points[b]) else shore).append((a, b))
                loop.append((a, b))
            loops.append(loop)
        surfaces.append(loops)
    line_id = {e: i + 1 for i, e in enumerate(shore + edge)}
    with open(path, "w") as fh:
        fh.write("// Written by bench/coastline/export_ocean.py (gmsh -setnumber hs S -setnumber "
                 "algo A).\nIf (!Exists(hs))\n  hs = 1;\nEndIf\nIf (!Exists(algo))\n  algo = 6;\n"
                 "EndIf\nMesh.Algorithm = algo;\n")
        for i, (x, y) in enumerate(points):
            fh.write(f"Point({i + 1}) = {{{x:.17g}, {y:.17g}, 0}};\n")
        for (a, b), i in line_id.items():
            fh.write(f"Line({i}) = {{{a + 1}, {b + 1}}};\n")
        loop_id = 0
        for s, loops in enumerate(surfaces):
            ids = []
            for loop in loops:
                loop_id += 1
                ids.append(loop_id)
                fh.write(f"Curve Loop({loop_id}) = {{{', '.join(str(line_id[e]) for e in loop)}}};\n")
            fh.write(f"Plane Surface({s + 1}) = {{{', '.join(map(str, ids))}}};\n")
        h_min, slope, h_max = grade
        fh.write(f"Field[1] = Distance;\nField[1].CurvesList = {{1:{len(shore)}}};\n"
                 "Field[1].NumPointsPerCurve = 5;\n"
                 f"Field[2] = Threshold;\nField[2].InField = 1;\n"
                 f"Field[2].SizeMin = hs * {h_min * h0!r};\nField[2].SizeMax = hs * {h_max * h0!r};\n"
                 f"Field[2].DistMin = 0;\nField[2].DistMax = {(h_max - h_min) / slope!r};\n"
                 "Background Field = 2;\nMesh.MeshSizeExtendFromBoundary = 0;\n"
                 "Mesh.MeshSizeFromPoints = 0;\nMesh.MeshSizeFromCurvature = 0;\n")
    return len(surfaces), len(points), len(shore)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("region")
    ap.add_argument("--to-crs", required=True)
    ap.add_argument("--clip", required=True)
    ap.add_argument("--h0", type=float, required=True)
    ap.add_argument("--simplify", type=float, default=0, help="tolerance F * h0")
    ap.add_argument("--grade", required=True, help="H_MIN,SLOPE,H_MAX")
    ap.add_argument("--feature", help="K,H_MIN,H_MAX: a feature-size term in the request")
    ap.add_argument("--gradation", type=float, default=0, help="the request's size gradation")
    ap.add_argument("--open", type=float, default=0,
                    help="close water narrower than F * h0 first (see opened_land)")
    ap.add_argument("--min-pocket", type=float, default=0,
                    help="with --open, sea pockets under M2 square metres become land")
    ap.add_argument("out")
    a = ap.parse_args()
    clip = [float(v) for v in a.clip.split(",")]
    grade = [float(v) for v in a.grade.split(",")]
    land = import_land(a.region, a.to_crs, clip, a.simplify * a.h0, a.open * a.h0 / 2,
                       a.min_pocket)
    if not land:
        sys.exit("export_ocean: no land inside the clip box")
    feature = [float(v) for v in a.feature.split(",")] if a.feature else None
    write_request(a.out + ".textproto", land, clip, a.h0, grade, feature, a.gradation)
    surfaces, points, shore = write_geo(a.out + ".geo", land, clip, a.h0, grade)
    holes = sum(len(h) for _, h in land)
    vertices = sum(len(o) + sum(len(h) for h in hs) for o, hs in land)
    print(f"export_ocean: {len(land)} polygons ({holes} holes, {vertices} vertices) -> "
          f"{a.out}.textproto; the sea: {surfaces} surfaces, {points} vertices, {shore} shoreline "
          f"edges -> {a.out}.geo")


if __name__ == "__main__":
    main()
