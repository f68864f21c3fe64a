#!/usr/bin/env python3
"""Reads tetrahedral mesh files back with real consumers and checks what they read.

    check_tet_files.py [--nodes N --tets M --boundary-faces F] --groups a,b [--group-faces 4,6]
                       --volume V FILES...

Every .msh / .msh22 / .vtu file is read with meshio and checked for the expected counts (where
given; otherwise every file must agree with the first), the physical groups ("domain" = tag 1,
dimension 3; group i of --groups = tag i + 2, dimension 2), the boundary triangles in each group
(--group-faces, where given; otherwise every file must agree with the first), positively oriented
tetrahedra, every node used, boundary triangles that are exactly the faces used by one
tetrahedron, turned outward, and the total volume within --tolerance (relative) of --volume.
Every .msh / .msh22 file is loaded by the gmsh CLI, which must exit 0 without errors and re-save
the same counts, groups and volume.

Exit status: 0 when every file passes, 1 when one fails, 77 (ctest's skip code) with
--skip-if-missing when meshio or gmsh is not available. Run it with the interpreter that has
meshio (Debian's python3-meshio is in /usr/bin/python3).
"""

import argparse
import os
import shutil
import subprocess
import sys
import tempfile

from check_mesh_files import SKIP, Failure, read_with_meshio, require


def cells_of(mesh, kind):
    import numpy as np
    blocks = [c.data for c in mesh.cells if c.type == kind]
    return np.concatenate(blocks) if blocks else np.zeros((0, 3 if kind == "triangle" else 4), int)


def faces_per_group(np, mesh, groups):
    """The number of boundary triangles in each of groups, by their physical tags."""
    key = "gmsh:physical" if "gmsh:physical" in mesh.cell_data else "physical"
    require(key in mesh.cell_data, f"no physical tags in the cell data {sorted(mesh.cell_data)}")
    tags = [np.asarray(data).ravel() for cells, data in zip(mesh.cells, mesh.cell_data[key])
            if cells.type == "triangle"]
    tags = np.concatenate(tags) if tags else np.zeros(0, int)
    return [int((tags == i + 2).sum()) for i in range(len(groups))]


def check_groups_and_volume(np, mesh, args, counts):
    """The physical groups, the triangles in each, and the tetrahedra's signed volume."""
    groups = {"domain": (1, 3), **{g: (i + 2, 2) for i, g in enumerate(args.groups)}}
    read = {name: tuple(np.asarray(v).ravel().tolist()) for name, v in mesh.field_data.items()}
    require(read == groups, f"physical groups {read}, expected {groups}")
    per_group = faces_per_group(np, mesh, args.groups)
    expected = counts.setdefault("group_faces", per_group)
    require(per_group == expected, f"triangles per group {per_group}, expected {expected}")
    points, tets = mesh.points, cells_of(mesh, "tetra")
    a, b, c, d = (points[tets[:, k]] for k in range(4))
    six_volume = np.einsum("ij,ij->i", b - a, np.cross(c - a, d - a))
    require((six_volume > 0).all(), f"{int((six_volume <= 0).sum())} tetrahedra not positive")
    volume = six_volume.sum() / 6
    require(abs(volume - args.volume) <= args.tolerance * args.volume,
            f"volume {volume:.6f}, expected {args.volume} within {args.tolerance:.1%}")
    return volume


def check_meshio(meshio, np, path, args, counts):
    mesh = read_with_meshio(meshio, path, "vtu" if path.endswith(".vtu") else "gmsh")
    points, tets, faces = mesh.points, cells_of(mesh, "tetra"), cells_of(mesh, "triangle")
    found = {"nodes": len(points), "tets": len(tets), "boundary_faces": len(faces)}
    for key, value in found.items():
        require(counts.setdefault(key, value) == value, f"{value} {key}, expected {counts[key]}")
    volume = check_groups_and_volume(np, mesh, args, counts)
    require(len(np.unique(tets)) == len(points), "some nodes are unused")
    # Faces used once, turned outward: each tetrahedron's faces as tet_boundary.h turns them.
    turned = np.concatenate([tets[:, [1, 2, 3]], tets[:, [0, 3, 2]], tets[:, [0, 1, 3]],
                             tets[:, [0, 2, 1]]])
    _, inverse, times = np.unique(np.sort(turned, axis=1), axis=0, return_inverse=True,
                                  return_counts=True)
    once = turned[times[inverse.ravel()] == 1]
    canonical = lambda f: tuple(np.roll(f, -int(np.argmin(f))).tolist())
    require({canonical(f) for f in once} == {canonical(f) for f in faces},
            "the boundary triangles are not the outward faces used once")
    return f"meshio: {found}, per group {counts['group_faces']}, volume {volume:.6f}"


def check_gmsh(gmsh, meshio, np, path, args, counts):
    with tempfile.TemporaryDirectory() as tmp:
        saved = os.path.join(tmp, "resaved.msh")
        run = subprocess.run([gmsh, path, "-save", "-format", "msh22", "-o", saved],
                             capture_output=True, text=True, timeout=600)
        log = run.stdout + run.stderr
        errors = [l for l in log.splitlines() if l.startswith("Error")]
        require(run.returncode == 0 and not errors,
                f"gmsh exit {run.returncode}: {' | '.join(errors) or log[-500:]}")
        mesh = read_with_meshio(meshio, saved, "gmsh")
    found = (len(mesh.points), len(cells_of(mesh, "tetra")), len(cells_of(mesh, "triangle")))
    expected = (counts["nodes"], counts["tets"], counts["boundary_faces"])
    require(found == expected, f"gmsh re-saved {found}, expected {expected}")
    try:
        volume = check_groups_and_volume(np, mesh, args, counts)
    except Failure as e:
        raise Failure(f"gmsh re-saved: {e}")
    return f"gmsh re-saved {found[0]} nodes, {found[1]} tetrahedra, {found[2]} triangles, " \
           f"groups {sorted(mesh.field_data)}, volume {volume:.6f}"


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--nodes", type=int)
    parser.add_argument("--tets", type=int)
    parser.add_argument("--boundary-faces", type=int)
    parser.add_argument("--groups", type=lambda s: s.split(","), required=True)
    parser.add_argument("--group-faces", type=lambda s: [int(n) for n in s.split(",")])
    parser.add_argument("--volume", type=float, required=True)
    parser.add_argument("--tolerance", type=float, default=1e-9)
    parser.add_argument("--gmsh", default=shutil.which("gmsh"))
    parser.add_argument("--skip-if-missing", action="store_true")
    parser.add_argument("files", nargs="+")
    args = parser.parse_args()
    try:
        import meshio
        import numpy as np
    except ImportError as e:
        print(f"SKIP: {e}")
        return SKIP if args.skip_if_missing else 1
    if args.gmsh is None and args.skip_if_missing:
        print("SKIP: gmsh not found")
        return SKIP
    counts = {k: v for k, v in (("nodes", args.nodes), ("tets", args.tets),
                                ("boundary_faces", args.boundary_faces),
                                ("group_faces", args.group_faces)) if v is not None}
    if args.group_faces is not None and len(args.group_faces) != len(args.groups):
        parser.error("--group-faces needs one count per group of --groups")
    failed = 0
    for path in args.files:
        try:
            notes = [check_meshio(meshio, np, path, args, counts)]
            if not path.endswith(".vtu"):
                notes.append(check_gmsh(args.gmsh, meshio, np, path, args, counts))
            print(f"ok   {path}: " + "; ".join(notes))
        except Failure as e:
            print(f"FAIL {path}: {e}")
            failed += 1
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
