#!/usr/bin/env python3
"""A plate with two holes, refined towards them, meshed on a meshd server through the meshd
Python package (python/; see its README for the install), and written with meshio.

    plate.py [--server HOST:PORT] [--h0 H0] [--deadline S] [OUT]

OUT's extension picks the format (.vtu by default, .msh, .xdmf, ...); the boundary groups
"plate" and "holes" become physical groups. On an error it prints the status, the server's
message and the field it names, and exits 1.
"""

import argparse
import sys

import meshd


def plate_request(h0):
    plate = meshd.rectangle((0, 0), (4, 2)).named("plate")
    holes = meshd.circle(0.4, center=(1, 1)) | meshd.circle(0.4, center=(3, 1))
    return meshd.request(plate - holes.named("holes"), h0=h0,
                         size=meshd.graded(holes, h_min=1, slope=2, h_max=3),
                         label="plate example")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("output", nargs="?", default="plate.vtu")
    parser.add_argument("--server", default="127.0.0.1:50051", help="meshd's HOST:PORT")
    parser.add_argument("--h0", type=float, default=0.02, help="edge length at the holes")
    parser.add_argument("--deadline", type=float, default=600, help="seconds (default 600)")
    args = parser.parse_args()

    with meshd.Client(args.server, timeout=args.deadline) as client:
        try:
            mesh = client.generate(plate_request(args.h0), progress=True)
        except meshd.MeshdError as e:
            field = f" (field {e.field})" if e.field else ""
            print(f"plate: {e}{field}", file=sys.stderr)
            return 1
    mesh.write(args.output)
    print(f"{mesh}\nwrote {args.output}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
