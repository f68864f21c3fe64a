#!/usr/bin/env python3
"""A V-belt pulley, revolved from its half cross-section, meshed with tetrahedra on a meshd
server through the meshd Python package, and written with meshio.

    pulley.py [--server HOST:PORT] [--h0 H0] [--deadline S] [OUT]

OUT's extension picks the format (.vtu by default, .msh, ...); the boundary group "pulley"
becomes a physical group of triangles. On an error it prints the status, the server's message
and the field it names, and exits 1.
"""

import argparse
import sys

import meshd

# The outline in (distance from the axis, height): hub with a bore, web, rim with a V groove.
CROSS_SECTION = [(0.2, -0.3), (0.45, -0.3), (0.45, -0.08), (0.85, -0.08), (0.85, -0.25),
                 (1.2, -0.25), (1.2, -0.15), (1.05, 0), (1.2, 0.15), (1.2, 0.25), (0.85, 0.25),
                 (0.85, 0.08), (0.45, 0.08), (0.45, 0.3), (0.2, 0.3)]


def pulley_request(h0):
    pulley = meshd.revolve(meshd.polygon(CROSS_SECTION)).named("pulley")
    return meshd.request(pulley, h0=h0, label="pulley example")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("output", nargs="?", default="pulley.vtu")
    parser.add_argument("--server", default="127.0.0.1:50051", help="meshd's HOST:PORT")
    parser.add_argument("--h0", type=float, default=0.06, help="edge length")
    parser.add_argument("--deadline", type=float, default=600, help="seconds (default 600)")
    args = parser.parse_args()

    with meshd.Client(args.server, timeout=args.deadline) as client:
        try:
            mesh = client.generate(pulley_request(args.h0), progress=True)
        except meshd.MeshdError as e:
            field = f" (field {e.field})" if e.field else ""
            print(f"pulley: {e}{field}", file=sys.stderr)
            return 1
    mesh.write(args.output)
    print(f"{mesh}\nwrote {args.output}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
