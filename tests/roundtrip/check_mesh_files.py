#!/usr/bin/env python3
"""Reads mesh files back with real consumers and checks what they read.

    check_mesh_files.py --nodes N --triangles M --boundary-edges E --groups a,b,c FILES...

Every .msh / .msh22 / .vtu file is read with meshio and checked for the expected counts, the
physical groups ("domain" = tag 1, dimension 2; group i of --groups = tag i + 2, dimension 1),
counter-clockwise triangles, every node used, and boundary lines that are exactly the edges used
by one triangle, oriented with the domain on their left. Where VTK's Python module is installed,
.vtu files are also read with VTK's own reader (ParaView's). Every .msh / .msh22 file is loaded
by the gmsh CLI, which must exit 0 without errors and re-save the same counts. Every .svg file
must be well-formed XML with one closed sub-path per triangle in its filled paths.

Exit status: 0 when every file passes, 1 when one fails, 2 on bad usage, 77 (ctest's skip code)
with --skip-if-missing when meshio or gmsh is not available.

Run it with the interpreter that has meshio (Debian's python3-meshio is in /usr/bin/python3).
"""

import argparse
import contextlib
import io
import os
import shutil
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET

SKIP = 77
DOMAIN_TAG = 1


def expected_groups(groups):
    """{name: (tag, dim)} as every writer numbers physical groups."""
    table = {"domain": (DOMAIN_TAG, 2)}
    for i, name in enumerate(groups):
        table[name] = (i + 2, 1)
    return table


class Failure(Exception):
    pass


def require(condition, message):
    if not condition:
        raise Failure(message)


# ---- meshio -----------------------------------------------------------------------------------


def read_with_meshio(meshio, path, file_format):
    """meshio.read with its stdout/stderr captured: meshio 5 prints failed attempts, warns through
    rich on stderr (e.g. an unclosed section) and calls sys.exit(1) when it cannot read a file."""
    out, err = io.StringIO(), io.StringIO()
    try:
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            mesh = meshio.read(path, file_format=file_format)
    except BaseException as e:  # SystemExit included
        raise Failure(f"meshio could not read it: {type(e).__name__}: {e} {out.getvalue()} "
                      f"{err.getvalue()}".strip())
    require("warning" not in err.getvalue().lower(), f"meshio warned: {err.getvalue().strip()}")
    return mesh


def boundary_of(np, triangles):
    """Directed edges used by exactly one triangle, as a set of (a, b) tuples."""
    half = np.concatenate([triangles[:, [0, 1]], triangles[:, [1, 2]], triangles[:, [2, 0]]])
    undirected = np.sort(half, axis=1)
    _, inverse, counts = np.unique(undirected, axis=0, return_inverse=True, return_counts=True)
    once = half[counts[inverse.ravel()] == 1]
    return set(map(tuple, once.tolist()))


def check_meshio(meshio, np, path, file_format, args):
    mesh = read_with_meshio(meshio, path, file_format)
    points = mesh.points
    require(points.shape == (args.nodes, 3) or points.shape == (args.nodes, 2),
            f"meshio read {points.shape[0]} points, expected {args.nodes}")
    if points.shape[1] == 3:
        require(np.all(points[:, 2] == 0), "points have non-zero z")

    physical_key = "gmsh:physical" if "gmsh:physical" in mesh.cell_data else "physical"
    require(physical_key in mesh.cell_data, f"no physical cell data (keys {list(mesh.cell_data)})")
    triangles, lines, line_tags = [], [], []
    for block, tags in zip(mesh.cells, mesh.cell_data[physical_key]):
        tags = np.asarray(tags).ravel()
        if block.type == "triangle":
            require(np.all(tags == DOMAIN_TAG), f"triangles carry physical tags {np.unique(tags)}")
            triangles.append(block.data)
        elif block.type == "line":
            lines.append(block.data)
            line_tags.append(tags)
        else:
            raise Failure(f"unexpected cell type {block.type}")
    triangles = np.concatenate(triangles) if triangles else np.zeros((0, 3), int)
    lines = np.concatenate(lines) if lines else np.zeros((0, 2), int)
    line_tags = np.concatenate(line_tags) if line_tags else np.zeros(0, int)
    require(len(triangles) == args.triangles,
            f"meshio read {len(triangles)} triangles, expected {args.triangles}")
    require(len(lines) == args.boundary_edges,
            f"meshio read {len(lines)} lines, expected {args.boundary_edges}")
    require(triangles.size == 0 or (triangles.min() >= 0 and triangles.max() < len(points)),
            "triangle indices out of range")

    groups = expected_groups(args.groups)
    names = {name: tuple(int(v) for v in np.asarray(value).ravel()[:2])
             for name, value in mesh.field_data.items()}
    require(names == groups, f"physical groups {names}, expected {groups}")
    group_tags = {tag for tag, dim in groups.values() if dim == 1}
    require(set(np.unique(line_tags).tolist()) <= group_tags,
            f"line physical tags {np.unique(line_tags)} not in {sorted(group_tags)}")
    per_group = {name: int(np.sum(line_tags == tag)) for name, (tag, dim) in groups.items()
                 if dim == 1}
    if args.group_edges:
        expected = dict(zip(args.groups, args.group_edges))
        require(per_group == expected, f"lines per group {per_group}, expected {expected}")

    xy = points[:, :2]
    a, b, c = xy[triangles[:, 0]], xy[triangles[:, 1]], xy[triangles[:, 2]]
    twice_area = (b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0])
    require(np.all(twice_area > 0), f"{int(np.sum(twice_area <= 0))} triangles are not "
            "counter-clockwise")
    if args.area is not None:
        area = 0.5 * float(twice_area.sum())
        require(abs(area - args.area) <= 1e-6 * max(1.0, abs(args.area)),
                f"area {area}, expected {args.area}")
    require(len(np.unique(triangles)) == len(points), "some nodes are used by no triangle")
    line_set = set(map(tuple, lines.tolist()))
    require(len(line_set) == len(lines), "some boundary lines are repeated")
    require(line_set == boundary_of(np, triangles),
            "boundary lines differ from the edges used by one triangle (or are reversed)")

    cells = ", ".join(f"{len(block.data)} {block.type}" for block in mesh.cells)
    data = sorted(k for k in mesh.cell_data if not k.startswith("gmsh:"))
    return (f"meshio: {len(points)} points; cells {cells}; groups "
            + ", ".join(f"{n}={t}/{d}" for n, (t, d) in names.items())
            + f"; lines per group {per_group}" + (f"; cell data {data}" if data else ""))


# ---- gmsh -------------------------------------------------------------------------------------


def parse_msh22(path):
    """A MSH 2.2 ASCII file as gmsh writes it: node count, {element type: count}, physical names
    {name: (tag, dim)}, and the number of triangles that are not counter-clockwise."""
    with open(path) as f:
        lines = f.read().split("\n")
    coords, types, names, not_ccw = {}, {}, {}, 0
    i = 0
    while i < len(lines):
        line = lines[i].strip()
        if line == "$PhysicalNames":
            for k in range(int(lines[i + 1])):
                dim, tag, name = lines[i + 2 + k].split(maxsplit=2)
                names[name.strip('"')] = (int(tag), int(dim))
        elif line == "$Nodes":
            count = int(lines[i + 1])
            for k in range(count):
                number, x, y, _ = lines[i + 2 + k].split()
                coords[int(number)] = (float(x), float(y))
            i += count
        elif line == "$Elements":
            count = int(lines[i + 1])
            for k in range(count):
                fields = lines[i + 2 + k].split()
                element_type, num_tags = int(fields[1]), int(fields[2])
                types[element_type] = types.get(element_type, 0) + 1
                if element_type == 2:
                    (ax, ay), (bx, by), (cx, cy) = (coords[int(v)] for v in fields[3 + num_tags:])
                    not_ccw += (bx - ax) * (cy - ay) - (by - ay) * (cx - ax) <= 0
            i += count
        i += 1
    return len(coords), types, names, not_ccw


def check_gmsh(gmsh, path, args):
    """gmsh loads the file and re-saves it as MSH 2.2; both must succeed and agree on counts."""
    with tempfile.TemporaryDirectory() as tmp:
        saved = os.path.join(tmp, "resaved.msh")
        try:
            run = subprocess.run([gmsh, path, "-save", "-format", "msh22", "-o", saved],
                                 capture_output=True, text=True, timeout=600)
        except subprocess.TimeoutExpired:
            raise Failure("gmsh timed out")
        log = run.stdout + run.stderr
        errors = [l for l in log.splitlines() if l.startswith("Error")]
        require(run.returncode == 0 and not errors,
                f"gmsh exit {run.returncode}: {' | '.join(errors) or log[-500:]}")
        require(os.path.exists(saved), "gmsh wrote no file")
        nodes, types, names, not_ccw = parse_msh22(saved)
    read_lines = [l.split(":", 1)[1].strip() for l in log.splitlines()
                  if l.startswith("Info") and ("nodes" in l or "elements" in l
                                               or "entities" in l) and "Reading" not in l]
    require(nodes == args.nodes, f"gmsh re-saved {nodes} nodes, expected {args.nodes}")
    require(types.get(2, 0) == args.triangles,
            f"gmsh re-saved {types.get(2, 0)} triangles, expected {args.triangles}")
    require(types.get(1, 0) == args.boundary_edges,
            f"gmsh re-saved {types.get(1, 0)} lines, expected {args.boundary_edges}")
    require(set(types) <= {1, 2}, f"gmsh re-saved element types {sorted(types)}")
    require(not_ccw == 0, f"gmsh re-saved {not_ccw} triangles that are not counter-clockwise")
    groups = expected_groups(args.groups)
    require(names == groups, f"gmsh physical groups {names}, expected {groups}")
    return f"gmsh: read {', '.join(read_lines)}; re-saved {nodes} nodes, {types.get(2, 0)} " \
           f"triangles, {types.get(1, 0)} lines, groups {sorted(names)}"


# ---- VTK (optional: ParaView's reader, when the vtk module is installed) -----------------------


def check_vtk(vtk, path, args):
    errors = []

    def on_error(caller, event):  # VTK reports parse errors through events, not exceptions
        errors.append(event)

    reader = vtk.vtkXMLUnstructuredGridReader()
    reader.AddObserver("ErrorEvent", on_error)
    reader.SetFileName(path)
    reader.Update()
    require(not errors, "VTK's reader reported errors (its messages are on stderr)")
    grid = reader.GetOutput()
    from vtk.util.numpy_support import vtk_to_numpy
    import numpy as np
    values, counts = np.unique(vtk_to_numpy(grid.GetCellTypesArray()), return_counts=True)
    types = {int(v): int(c) for v, c in zip(values, counts)}
    require(grid.GetNumberOfPoints() == args.nodes,
            f"VTK read {grid.GetNumberOfPoints()} points, expected {args.nodes}")
    require(types.get(5, 0) == args.triangles and types.get(3, 0) == args.boundary_edges,
            f"VTK read cell types {types}, expected {args.triangles} triangles (5) and "
            f"{args.boundary_edges} lines (3)")
    quality = grid.GetCellData().GetArray("quality")
    require(quality is not None, "VTK found no quality array")
    low, high = quality.GetRange()
    return f"vtk {vtk.vtkVersion.GetVTKVersion()}: {grid.GetNumberOfPoints()} points, cell " \
           f"types {types}, quality range [{low:.4f}, {high:.4f}]"


# ---- svg --------------------------------------------------------------------------------------


def check_svg(path, args):
    try:
        root = ET.parse(path).getroot()
    except ET.ParseError as e:
        raise Failure(f"not well-formed XML: {e}")
    require(root.tag == "{http://www.w3.org/2000/svg}svg", f"root element is {root.tag}")
    require("viewBox" in root.attrib, "no viewBox")
    closed = 0
    for element in root.iter("{http://www.w3.org/2000/svg}path"):
        if element.get("fill", "black") != "none":
            closed += element.get("d", "").count("z")
    require(closed == args.triangles, f"{closed} filled triangles drawn, expected {args.triangles}")
    return f"svg: well-formed, {closed} triangles drawn, viewBox {root.get('viewBox')}"


# ---- main -------------------------------------------------------------------------------------


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--nodes", type=int, required=True)
    parser.add_argument("--triangles", type=int, required=True)
    parser.add_argument("--boundary-edges", type=int, required=True)
    parser.add_argument("--groups", type=lambda s: [g for g in s.split(",") if g], default=[],
                        help="boundary group names in boundary_names order, comma-separated")
    parser.add_argument("--group-edges", type=lambda s: [int(v) for v in s.split(",")],
                        help="optional: boundary edges per group, in --groups order")
    parser.add_argument("--area", type=float, help="optional: expected total area")
    parser.add_argument("--gmsh", default=None, help="gmsh executable (default: gmsh on PATH)")
    parser.add_argument("--no-gmsh", action="store_true", help="skip the gmsh CLI check")
    parser.add_argument("--no-meshio", action="store_true",
                        help="skip the meshio check of .msh/.msh22 files (to test gmsh alone)")
    parser.add_argument("--skip-if-missing", action="store_true",
                        help="exit 77 when meshio or gmsh is missing instead of failing")
    parser.add_argument("files", nargs="+")
    args = parser.parse_args()
    if args.group_edges and len(args.group_edges) != len(args.groups):
        parser.error("--group-edges needs one count per group")

    def missing(what):
        message = f"{what} is not available to {sys.executable}"
        if args.skip_if_missing:
            print(f"SKIP: {message}; install python3-meshio and gmsh to run this check")
            sys.exit(SKIP)
        print(f"FAIL: {message}")
        sys.exit(1)

    try:
        import meshio
        import numpy as np
    except ImportError as e:
        missing(f"meshio ({e})")
    gmsh = None
    if not args.no_gmsh and any(f.endswith((".msh", ".msh22")) for f in args.files):
        gmsh = args.gmsh or shutil.which("gmsh")
        if not gmsh or not os.access(gmsh, os.X_OK):
            missing("the gmsh executable")

    try:  # optional: only some machines have VTK's Python module
        import vtk
    except ImportError:
        vtk = None

    passed = failed = 0
    for path in args.files:
        reports = []
        try:
            if path.endswith((".msh", ".msh22")):
                if not args.no_meshio:
                    reports.append(check_meshio(meshio, np, path, "gmsh", args))
                if gmsh:
                    reports.append(check_gmsh(gmsh, path, args))
            elif path.endswith(".vtu"):
                reports.append(check_meshio(meshio, np, path, "vtu", args))
                if vtk:
                    reports.append(check_vtk(vtk, path, args))
            elif path.endswith(".svg"):
                reports.append(check_svg(path, args))
            else:
                raise Failure("unknown extension (expected .msh, .msh22, .vtu or .svg)")
        except Failure as e:
            failed += 1
            print(f"FAIL {path}: {e}")
            for report in reports:
                print(f"    {report}")
            continue
        passed += 1
        print(f"ok   {path}")
        for report in reports:
            print(f"    {report}")
    print(f"check_mesh_files: {passed} passed, {failed} failed")
    return 0 if failed == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
