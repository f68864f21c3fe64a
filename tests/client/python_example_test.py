#!/usr/bin/env python3
"""examples/python/meshd_client.py against a real meshd, as a user would run it.

    python_example_test.py --meshd BIN --python-stubs DIR --client CLIENT.py --request G1.textproto

Starts `BIN --listen 127.0.0.1:0 --backend cpu`, runs the client on the request writing a .vtu,
reads the file back with meshio and compares its node and triangle counts with the summary the
client printed, and the same for a small volume's tetrahedra; then checks that a bad request makes
the client exit non-zero with the server's message and write nothing.

Exit status: 0 when all pass, 1 on a failure, 77 (ctest's skip) when grpcio or meshio is missing.
"""

import argparse
import os
import re
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from meshd_child import MeshdChild  # noqa: E402

SKIP = 77


def run_client(args, *rest):
    cmd = [sys.executable, args.client, "--server", args.address, "--stubs", args.python_stubs,
           "--deadline", "120", *rest]
    return subprocess.run(cmd, capture_output=True, text=True, timeout=180)


def test_g1_to_vtu(args, tmp):
    import meshio
    out = os.path.join(tmp, "g1.vtu")
    r = run_client(args, args.request, out)
    assert r.returncode == 0, f"exit {r.returncode}\n{r.stderr}"
    assert "queued" in r.stderr and "started on" in r.stderr, f"no progress on stderr:\n{r.stderr}"
    m = re.search(r"^nodes (\d+) triangles (\d+) ", r.stdout, re.M)
    assert m, f"no summary in stdout:\n{r.stdout}"
    nodes, triangles = int(m.group(1)), int(m.group(2))
    mesh = meshio.read(out)
    read_triangles = sum(len(c.data) for c in mesh.cells if c.type == "triangle")
    assert (len(mesh.points), read_triangles) == (nodes, triangles), \
        f"{out} has {len(mesh.points)} nodes, {read_triangles} triangles; the summary says " \
        f"{nodes}, {triangles}"
    # G1 at h0 0.04 is about 2,270 nodes (examples/g1_disk.textproto).
    assert 2000 < nodes < 2600, f"{nodes} nodes for G1"
    print(f"  {nodes} nodes, {triangles} triangles read back from the .vtu")


def test_volume_to_vtu(args, tmp):
    """A volume request (a cube minus a ball, about 800 nodes) comes back as tetrahedra."""
    import meshio
    request = os.path.join(tmp, "part.textproto")
    with open(request, "w") as f:
        f.write("volume { geometry { difference {\n"
                "  base { box { min { x: -1 y: -1 z: -1 } max { x: 1 y: 1 z: 1 } } }\n"
                "  subtract { sphere { radius: 0.5 } } } } }\nh0: 0.25\n")
    out = os.path.join(tmp, "part.vtu")
    r = run_client(args, request, out)
    assert r.returncode == 0, f"exit {r.returncode}\n{r.stderr}"
    m = re.search(r"^nodes (\d+) tetrahedra (\d+) ", r.stdout, re.M)
    assert m, f"no summary in stdout:\n{r.stdout}"
    nodes, tetrahedra = int(m.group(1)), int(m.group(2))
    mesh = meshio.read(out)
    read_tetrahedra = sum(len(c.data) for c in mesh.cells if c.type == "tetra")
    assert (len(mesh.points), read_tetrahedra) == (nodes, tetrahedra), \
        f"{out} has {len(mesh.points)} nodes, {read_tetrahedra} tetrahedra; the summary says " \
        f"{nodes}, {tetrahedra}"
    assert 500 < nodes < 2000, f"{nodes} nodes for the cube minus a ball at h0 0.25"
    print(f"  {nodes} nodes, {tetrahedra} tetrahedra read back from the .vtu")


def test_bad_request(args, tmp):
    bad = os.path.join(tmp, "bad.textproto")
    with open(bad, "w") as f:
        f.write("geometry { circle { radius: 1 } }\nh0: -1\n")
    out = os.path.join(tmp, "bad.vtu")
    r = run_client(args, bad, out)
    assert r.returncode != 0, "a bad request exited 0"
    assert "INVALID_ARGUMENT" in r.stderr and "h0:" in r.stderr, f"stderr:\n{r.stderr}"
    assert not os.path.exists(out), "a failed request wrote its output"
    print(f"  exit {r.returncode}: {r.stderr.strip()}")


def main():
    parser = argparse.ArgumentParser()
    for flag in ("--meshd", "--python-stubs", "--client", "--request"):
        parser.add_argument(flag, required=True)
    args = parser.parse_args()
    try:
        import grpc  # noqa: F401
        import meshio  # noqa: F401
    except ImportError as e:
        print(f"SKIP: {e} (needs python3-grpcio and python3-meshio)")
        return SKIP

    failures = 0
    with MeshdChild(args.meshd) as meshd, tempfile.TemporaryDirectory() as tmp:
        args.address = meshd.address
        tests = (test_g1_to_vtu, test_volume_to_vtu, test_bad_request)
        for test in tests:
            t = time.monotonic()
            try:
                test(args, tmp)
                print(f"PASS {test.__name__} ({time.monotonic() - t:.1f} s)")
            except (AssertionError, subprocess.TimeoutExpired) as e:
                failures += 1
                print(f"FAIL {test.__name__}: {e}\n  meshd's log:\n  {meshd.log()}")
    print(f"{failures} of {len(tests)} sub-tests failed" if failures
          else f"all {len(tests)} sub-tests passed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
