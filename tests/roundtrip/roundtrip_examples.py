#!/usr/bin/env python3
"""Meshes the G1-G5 examples with meshbench and reads every file back with meshio and gmsh.

    roundtrip_examples.py --meshbench BIN --out DIR [--gmsh GMSH] EXAMPLES_DIR

For each example, meshbench writes .msh (4.1 ASCII), .msh22, .vtu and .svg into DIR; the node
and triangle counts come from meshbench's table row, and check_mesh_files.py (beside this file,
run with this interpreter) checks that every consumer reads those counts and the expected
physical groups. MSH 4.1 binary stays with the unit round trip (mesh_roundtrip_read): meshbench
picks formats by extension and binary has none.

The boundary-edge count is not in meshbench's table; it follows from Euler's formula for a
connected triangulated domain with H holes, V - E + T = 1 - H with 2E = 3T + B, so
B = 2V - T - 2 + 2H. A mesh with a stray component or an extra hole therefore fails too.

Exit status: 0 when all pass, 1 on a failure, 77 (ctest's skip) when meshio or gmsh is missing.
"""

import argparse
import os
import subprocess
import sys

SKIP = 77

# Example stem -> (boundary group names in boundary_names order, number of holes). The names are
# the `name:` fields of examples/*.textproto, outer shape first.
EXPECTED = {
    "g1_disk": (["outer"], 0),
    "g2_square_hole": (["outer", "hole"], 1),
    "g3_polygon": (["outer"], 0),
    "g4_ellipse": (["outer"], 0),
    "g5_graded_hole": (["outer", "hole"], 1),
}
FORMATS = ["msh", "msh22", "vtu", "svg"]


def table_rows(text):
    """{request stem: {column: cell}} from meshbench's Markdown table."""
    lines = [l for l in text.splitlines() if l.startswith("|")]
    header = [c.strip() for c in lines[0].strip("|").split("|")]
    rows = {}
    for line in lines[2:]:
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        rows[cells[0]] = dict(zip(header, cells))
    return rows


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--meshbench", required=True, help="the meshbench executable")
    parser.add_argument("--out", required=True, help="directory for the mesh files")
    parser.add_argument("--gmsh", default=None, help="gmsh executable (default: gmsh on PATH)")
    parser.add_argument("examples", help="the examples/ directory")
    args = parser.parse_args()

    try:  # skip before meshing anything when the readers are missing
        import meshio  # noqa: F401
    except ImportError as e:
        print(f"SKIP: meshio is not available to {sys.executable} ({e}); install python3-meshio")
        return SKIP

    os.makedirs(args.out, exist_ok=True)
    requests = [os.path.join(args.examples, f"{stem}.textproto") for stem in EXPECTED]
    outputs = [a for f in FORMATS for a in ("-o", os.path.join(args.out, "{name}." + f))]
    run = subprocess.run([args.meshbench, *outputs, *requests], capture_output=True, text=True)
    print(run.stdout, end="")
    print(run.stderr, end="", file=sys.stderr)
    if run.returncode != 0:
        print(f"FAIL: meshbench exited {run.returncode}")
        return 1
    rows = table_rows(run.stdout)

    # One checker per example, all at once: each spends most of its time starting Python, meshio
    # and gmsh, so running them side by side keeps the test to a few seconds.
    check = os.path.join(os.path.dirname(os.path.abspath(__file__)), "check_mesh_files.py")
    checks, failed = {}, []
    for stem, (groups, holes) in EXPECTED.items():
        if stem not in rows:
            print(f"FAIL: no table row for {stem}")
            failed.append(stem)
            continue
        nodes, triangles = int(rows[stem]["nodes"]), int(rows[stem]["triangles"])
        boundary_edges = 2 * nodes - triangles - 2 + 2 * holes
        command = [sys.executable, check, "--skip-if-missing",
                   "--nodes", str(nodes), "--triangles", str(triangles),
                   "--boundary-edges", str(boundary_edges), "--groups", ",".join(groups)]
        if args.gmsh:
            command += ["--gmsh", args.gmsh]
        command += [os.path.join(args.out, f"{stem}.{f}") for f in FORMATS]
        title = (f"{stem}: {nodes} nodes, {triangles} triangles, {boundary_edges} boundary edges, "
                 f"groups {groups}")
        checks[stem] = (title, subprocess.Popen(command, stdout=subprocess.PIPE,
                                                stderr=subprocess.STDOUT, text=True))
    codes = {}
    for stem, (title, process) in checks.items():
        output, _ = process.communicate()
        codes[stem] = process.returncode
        print(f"\n== {title}\n{output}", end="")
    if SKIP in codes.values():
        return SKIP
    failed += [stem for stem, code in codes.items() if code != 0]
    print(f"\nroundtrip_examples: {len(EXPECTED) - len(failed)} passed, {len(failed)} failed"
          + (f" ({', '.join(failed)})" if failed else ""))
    return 0 if not failed else 1


if __name__ == "__main__":
    sys.exit(main())
