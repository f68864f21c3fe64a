#!/usr/bin/env python3
"""meshctl against a real meshd: every command, its output and its exit code (client/exit_codes.h).

    meshctl_test.py --meshd BIN --meshctl BIN --examples DIR

Starts `meshd --listen 127.0.0.1:0 --backend cpu --queue-capacity 2` and runs the sub-tests
below against it, one line PASS or FAIL each; the drain sub-test starts a meshd of its own.
meshio, when the interpreter has it, reads the written .msh and .vtu back.

Exit status: 0 when all pass, 1 on a failure.
"""

import argparse
import contextlib
import io
import json
import math
import os
import re
import signal
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from meshd_child import MeshdChild  # noqa: E402

# Exit codes, as client/exit_codes.h defines them.
OK, BAD_REQUEST, UNAVAILABLE, DEADLINE, CANCELLED, TOO_LARGE, NOT_FOUND = 0, 2, 3, 4, 5, 6, 7
FAILED_PRECONDITION, NOT_SERVING, BAD_RESULT = 9, 10, 11

# A disk of ~1,400 nodes that never settles (dptol 1e-9): a job that runs until cancelled.
LONG_REQUEST = """geometry { circle { radius: 1 } }
h0: 0.05
params { dptol: 1e-9 max_iterations: 1000000 }
"""


class Context:
    def __init__(self, args, server, tmp):
        self.meshd_bin, self.meshctl_bin, self.examples = args.meshd, args.meshctl, args.examples
        self.server, self.tmp = server, tmp
        self.long = self.path("long.textproto")
        with open(self.long, "w") as f:
            f.write(LONG_REQUEST)

    def path(self, name):
        return os.path.join(self.tmp, name)

    def example(self, name):
        return os.path.join(self.examples, name)

    def run(self, *argv, server=None, timeout=120):
        """meshctl ARGV with --server and a default --deadline (a later --deadline wins)."""
        cmd = [self.meshctl_bin, "--server", server or self.server, "--deadline", "60", *argv]
        return subprocess.run(cmd, capture_output=True, text=True, timeout=timeout, cwd=self.tmp)

    def expect(self, code, *argv, **kw):
        r = self.run(*argv, **kw)
        assert r.returncode == code, (f"meshctl {' '.join(argv)}: exit {r.returncode}, wanted "
                                      f"{code}\n  stdout: {r.stdout.strip()}\n  stderr: "
                                      f"{r.stderr.strip()}")
        return r

    def wait_state(self, job_id, state, timeout=30, server=None):
        deadline = time.monotonic() + timeout
        while True:
            out = self.expect(OK, "status", job_id, server=server).stdout
            if f" {state} " in out + " ":
                return out
            assert time.monotonic() < deadline, f"{job_id} not {state} after {timeout} s: {out}"
            time.sleep(0.05)


def summary_nodes(stdout):
    m = re.search(r"nodes (\d+)\s+triangles (\d+)", stdout)
    assert m, f"no summary in:\n{stdout}"
    return int(m.group(1))


def meshio_nodes(path):
    try:
        import meshio
    except ImportError:
        return None
    with contextlib.redirect_stdout(io.StringIO()):  # its MSH reader prints an empty line
        return len(meshio.read(path).points)


# ---- sub-tests -----------------------------------------------------------------------------------

def test_health(c):
    r = c.expect(OK, "health")
    assert r.stdout.strip() == "SERVING", r.stdout


def test_generate_files(c):
    r = c.expect(OK, "generate", c.example("g1_disk.textproto"), "-o", "a.msh", "-o", "a.vtu",
                 "-o", "a.svg")
    nodes = summary_nodes(r.stdout)
    for name in ("a.msh", "a.vtu", "a.svg"):
        assert f"wrote {name}" in r.stdout, r.stdout
        assert os.path.getsize(c.path(name)) > 0, name
    with open(c.path("a.svg")) as f:
        assert "<svg" in f.read(512), "a.svg is no SVG"
    read = {name: meshio_nodes(c.path(name)) for name in ("a.msh", "a.vtu")}
    if None not in read.values():
        assert read == {"a.msh": nodes, "a.vtu": nodes}, f"meshio read {read}, summary {nodes}"
    print(f"  {nodes} nodes; meshio read back {read}")


def test_generate_json(c):
    r = c.expect(OK, "generate", "--circle", "1", "--h0", "0.1", "--json")
    events = [json.loads(line) for line in r.stdout.splitlines()]  # every line is JSON
    assert events and "queued" in events[0], f"first event: {events[:1]}"
    done = [e["done"] for e in events if "done" in e]
    assert len(done) == 1 and int(done[0]["nodes"]) > 0, f"done events: {done}"
    print(f"  {len(events)} events, done with {done[0]['nodes']} nodes")


def test_frames(c):
    r = c.expect(OK, "generate", c.example("g1_disk.textproto"), "--frames", "frames")
    frames = sorted(f for f in os.listdir(c.path("frames")) if re.fullmatch(r"frame_\d{6}\.svg", f))
    assert frames, "no frames written"
    assert f"wrote {len(frames)} frames" in r.stdout, r.stdout
    print(f"  {len(frames)} frames, {frames[0]} .. {frames[-1]}")


def test_bad_request(c):
    r = c.expect(BAD_REQUEST, "generate", "--circle", "1", "--h0", "-1")
    assert "h0:" in r.stderr, r.stderr


def test_gpu_on_cpu_server(c):
    r = c.expect(FAILED_PRECONDITION, "generate", "--circle", "1", "--h0", "0.1",
                 "--backend", "gpu")
    assert "FAILED_PRECONDITION" in r.stderr, r.stderr


def test_too_large(c):
    r = c.expect(TOO_LARGE, "generate", "--circle", "1", "--h0", "1e-5")
    assert "RESOURCE_EXHAUSTED" in r.stderr and "h0" in r.stderr, r.stderr


def test_submit_watch_status_list(c):
    job_id = c.expect(OK, "submit", c.example("g1_disk.textproto")).stdout.strip()
    assert re.fullmatch(r"\S+", job_id), f"submit printed {job_id!r}"
    c.expect(OK, "watch", job_id, "-o", "x.msh")
    assert os.path.getsize(c.path("x.msh")) > 0
    status = c.expect(OK, "status", job_id).stdout
    assert status.startswith(job_id) and "SUCCEEDED" in status, status
    listed = [l for l in c.expect(OK, "list").stdout.splitlines() if l.startswith(job_id)]
    assert len(listed) == 1 and "SUCCEEDED" in listed[0], f"list: {listed}"
    c.expect(NOT_FOUND, "status", "nope")
    c.expect(NOT_FOUND, "watch", "nope")


def test_queue_full_and_cancel(c):
    # One CPU worker runs the first long job; --queue-capacity 2 lets two more wait.
    running = c.expect(OK, "submit", c.long).stdout.strip()
    c.wait_state(running, "RUNNING")
    queued = [c.expect(OK, "submit", c.long).stdout.strip() for _ in range(2)]
    r = c.expect(UNAVAILABLE, "submit", c.long)
    assert "full" in r.stderr, r.stderr
    watch = subprocess.Popen([c.meshctl_bin, "--server", c.server, "watch", running],
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        time.sleep(0.3)  # let the watch stream start
        for job_id in [running, *queued]:
            c.expect(OK, "cancel", job_id)
        out, err = watch.communicate(timeout=60)
    finally:
        watch.kill()
    assert watch.returncode == CANCELLED, f"watch exit {watch.returncode}, wanted 5: {err}"
    assert "CANCELLED" in err, err
    for job_id in [running, *queued]:
        c.wait_state(job_id, "CANCELLED")


def test_deadline(c):
    t = time.monotonic()
    r = c.expect(DEADLINE, "generate", c.long, "--deadline", "0.5")
    assert "DEADLINE_EXCEEDED" in r.stderr, r.stderr
    assert time.monotonic() - t < 10, "the deadline was not kept"
    # The server cancels the job of a call whose deadline passed.
    job_id = re.search(r"job (\S+) queued", r.stderr).group(1)
    c.wait_state(job_id, "CANCELLED")


def test_unreachable(c):
    r = c.expect(UNAVAILABLE, "health", "--deadline", "5", server="127.0.0.1:1")
    assert "UNAVAILABLE" in r.stderr, r.stderr


def test_command_line(c):
    r = c.expect(BAD_REQUEST, "generate", "--circle", "1", "--h0", "0.1", "--no-such-flag")
    assert "--no-such-flag" in r.stderr, r.stderr
    c.expect(BAD_REQUEST, "frobnicate")
    c.expect(BAD_REQUEST, "generate")  # no request
    c.expect(BAD_REQUEST, "status")  # no job id
    c.expect(BAD_REQUEST, "generate", "--circle", "1", "--h0", "0.1", "-o", "mesh.xyz")


def test_output_file_error(c):
    # The job succeeds, the file cannot be created (its folder is a file): 11, not 2.
    r = c.expect(BAD_RESULT, "generate", "--circle", "1", "--h0", "0.1", "-o",
                 os.path.join(c.path("a.svg"), "mesh.msh"))
    assert "cannot create" in r.stderr, r.stderr


def test_import(c):
    """--import of examples/gis/: the island alone, the sea round it from the example request, and
    a bad filter (exit 2, the flag named)."""
    island = c.example(os.path.join("gis", "island.geojson"))
    r = c.expect(OK, "generate", "--import", island, "--h0", "800", "-o", "island.vtu")
    assert "imported 3 polygons" in r.stderr and "UTM zone 25N" in r.stderr, r.stderr
    nodes = summary_nodes(r.stdout)
    read = meshio_nodes(c.path("island.vtu"))
    assert read in (None, nodes), f"meshio read {read} nodes, summary {nodes}"
    r = c.expect(OK, "generate", c.example(os.path.join("gis", "island_ocean.textproto")),
                 "--import", island, "--h0", "1000", "-o", "sea.msh")
    print(f"  island {nodes} nodes, sea {summary_nodes(r.stdout)} nodes")
    r = c.expect(BAD_REQUEST, "generate", "--import", island, "--h0", "800", "--where", "x >")
    assert "--where:" in r.stderr and "island.geojson" in r.stderr, r.stderr


def test_request(c):
    """meshctl request writes the request generate would send, with no server there; meshing
    that file gives the mesh the flags give."""
    shape = ("--circle", "1", "--hole", "0.3", "--h0", "0.1", "--seed", "7")
    c.expect(OK, "request", *shape, "-o", "annulus.textproto", server="127.0.0.1:1")
    r = c.expect(OK, "request", *shape, server="127.0.0.1:1")
    assert "proto-message: meshd.v1.MeshRequest" in r.stdout and "h0: 0.1" in r.stdout, r.stdout
    from_flags = summary_nodes(c.expect(OK, "generate", *shape).stdout)
    from_file = summary_nodes(c.expect(OK, "generate", c.path("annulus.textproto")).stdout)
    assert from_flags == from_file, f"flags {from_flags} nodes, file {from_file}"
    r = c.expect(BAD_REQUEST, "request", *shape, "-o", "a.textproto", "-o", "b.textproto")
    assert "-o:" in r.stderr, r.stderr


def write_npy(path, rows):
    """rows (a list of lists of floats) as a float32 .npy, written by hand: no numpy needed."""
    import struct
    shape = (len(rows), len(rows[0])) if rows and isinstance(rows[0], list) else (len(rows),)
    flat = [v for row in rows for v in row] if len(shape) == 2 else rows
    header = f"{{'descr': '<f4', 'fortran_order': False, 'shape': {shape!r}, }}"
    header += " " * (-(10 + len(header) + 1) % 64) + "\n"
    with open(path, "wb") as f:
        f.write(b"\x93NUMPY\x01\x00" + struct.pack("<H", len(header)) + header.encode())
        f.write(struct.pack(f"<{len(flat)}f", *flat))


def mesh_area(path):
    """The area of the triangles of a .vtu, through meshio; None without it."""
    try:
        import meshio
    except ImportError:
        return None
    m = meshio.read(path)
    p, t = m.points, m.cells_dict["triangle"]
    return sum(0.5 * abs((p[b][0] - p[a][0]) * (p[d][1] - p[a][1]) -
                         (p[d][0] - p[a][0]) * (p[b][1] - p[a][1])) for a, b, d in t)


def test_sdf_grid(c):
    """--sdf-grid: a disk of radius 0.8 sampled on a 41 x 41 grid (its area comes back), the
    segmented-image example where numpy is at hand, and bad grids and flags (exit 2, named)."""
    h = 0.05
    disk = [[math.hypot(-1 + i * h, -1 + j * h) - 0.8 for i in range(41)] for j in range(41)]
    write_npy(c.path("disk.npy"), disk)
    r = c.expect(OK, "generate", "--sdf-grid", "disk.npy", "--sdf-grid-origin", "-1,-1",
                 "--sdf-grid-spacing", str(h), "--h0", "0.08", "-o", "disk.vtu", "-o", "disk.svg")
    nodes = summary_nodes(r.stdout)
    area = mesh_area(c.path("disk.vtu"))
    assert area is None or abs(area / (math.pi * 0.64) - 1) < 0.01, f"area {area}"
    with open(c.path("disk.svg")) as f:
        assert "disk" in f.read(), "the boundary group is not named after the file"
    print(f"  disk {nodes} nodes, area {area}")
    try:
        import numpy  # noqa: F401
        script = c.example(os.path.join("segmented_image", "make_sdf.py"))
        subprocess.run([sys.executable, script, c.path("blob.npy")], check=True,
                       capture_output=True, timeout=60)
        r = c.expect(OK, "generate", "--sdf-grid", "blob.npy", "--sdf-grid-spacing", "0.01",
                     "--h0", "0.04")
        q_min = float(re.search(r"q_min ([0-9.]+)", r.stdout).group(1))
        assert q_min > 0.5, r.stdout
        print(f"  segmented image {summary_nodes(r.stdout)} nodes, q_min {q_min}")
    except ImportError:
        print("  no numpy: the segmented-image example skipped")

    disk[3][5] = float("nan")
    write_npy(c.path("nan.npy"), disk)
    r = c.expect(BAD_REQUEST, "generate", "--sdf-grid", "nan.npy", "--h0", "0.1")
    assert "--sdf-grid:" in r.stderr and "nan.npy" in r.stderr and "[3, 5]" in r.stderr, r.stderr
    write_npy(c.path("line.npy"), [-1.0, 1.0, 2.0])
    r = c.expect(BAD_REQUEST, "generate", "--sdf-grid", "line.npy", "--h0", "0.1")
    assert "shape (3)" in r.stderr, r.stderr
    write_npy(c.path("empty.npy"), [[1.0, 2.0], [3.0, 4.0]])  # the server's check
    r = c.expect(BAD_REQUEST, "generate", "--sdf-grid", "empty.npy", "--h0", "0.1")
    assert "geometry.distance_grid.values" in r.stderr and "no value < 0" in r.stderr, r.stderr
    r = c.expect(BAD_REQUEST, "generate", "--circle", "1", "--h0", "0.1", "--sdf-grid-origin",
                 "0,0")
    assert "--sdf-grid-origin: only with --sdf-grid" in r.stderr, r.stderr
    r = c.expect(BAD_REQUEST, "generate", "--sdf-grid", "disk.npy", "--circle", "1", "--h0", "1")
    assert "--sdf-grid: give it alone" in r.stderr, r.stderr
    r = c.expect(BAD_REQUEST, "generate", "--sdf-grid", "disk.npy", "--h0", "0.1",
                 "--sdf-grid-spacing", "0")
    assert "--sdf-grid-spacing: must be > 0" in r.stderr, r.stderr


def mean_edges(path):
    """Mean edge length of the triangles left of x = -1 and right of x = 1, or None without
    meshio."""
    try:
        import meshio
    except ImportError:
        return None
    with contextlib.redirect_stdout(io.StringIO()):
        mesh = meshio.read(path)
    left, right = [], []
    for tri in mesh.cells_dict["triangle"]:
        for a, b in ((tri[0], tri[1]), (tri[1], tri[2]), (tri[2], tri[0])):
            (xa, ya), (xb, yb) = mesh.points[a][:2], mesh.points[b][:2]
            length, mid = ((xa - xb) ** 2 + (ya - yb) ** 2) ** 0.5, (xa + xb) / 2
            (left if mid < -1 else right if mid > 1 else []).append(length)
    return sum(left) / len(left), sum(right) / len(right)


def test_size_grid(c):
    """--size-grid with a .npy: a 4 x 2 rectangle, sizes 1 on the left to 3 on the right (edges
    growing by 0.05 per unit at h0 0.1); then --gradation 0.02, which slows that growth, and the
    errors: no origin, a NaN in the file (the index named), a gradation out
    of the server's range (the field named)."""
    rows = [[1 + 0.5 * i for i in range(5)] for _ in range(3)]  # [j][i], x = -2 + i, y = -1 + j
    write_npy(c.path("sizes.npy"), rows)
    grid = ["--size-grid", "sizes.npy", "--size-grid-origin", "-2,-1", "--size-grid-spacing", "1"]
    base = ["generate", "--rectangle", "4,2", "--h0", "0.1"]
    uniform = summary_nodes(c.expect(OK, *base).stdout)
    r = c.expect(OK, *base, *grid, "-o", "grid.vtu")
    graded = summary_nodes(r.stdout)
    # 1 / h^2 integrates to a third of the rectangle's area.
    assert 0.25 * uniform < graded < 0.45 * uniform, f"{graded} nodes, uniform {uniform}"
    edges = mean_edges(c.path("grid.vtu"))
    if edges is not None:  # h averages 1.25 left of x = -1, 2.75 right of x = 1
        assert 1.8 < edges[1] / edges[0] < 2.6, f"mean edges left, right: {edges}"
    limited = summary_nodes(c.expect(OK, *base, *grid, "--gradation", "0.02").stdout)
    assert limited > 1.2 * graded, f"{limited} nodes with --gradation, {graded} without"
    print(f"  uniform {uniform} nodes, grid {graded}, grid with gradation {limited}; "
          f"edges left, right {edges}")

    r = c.expect(BAD_REQUEST, *base, "--size-grid", "sizes.npy", "--size-grid-spacing", "1")
    assert "--size-grid-origin:" in r.stderr and "required" in r.stderr, r.stderr
    rows[1][2] = float("nan")
    write_npy(c.path("holes.npy"), rows)
    r = c.expect(BAD_REQUEST, *base, *grid[:1], "holes.npy", *grid[2:])
    assert "--size-grid:" in r.stderr and "holes.npy" in r.stderr and "[1, 2]" in r.stderr, \
        r.stderr
    r = c.expect(BAD_REQUEST, *base, *grid, "--gradation", "20")
    assert "size.gradation" in r.stderr and "(0, 10]" in r.stderr, r.stderr


def test_feature(c):
    """--feature: two unit squares joined by a channel 0.1 wide; at h0 0.1 the channel is one
    edge across, with --feature 4,0.1,1 about four, so the mesh gains nodes; then a count of
    elements out of the server's range (the field named)."""
    with open(c.path("dumbbell.textproto"), "w") as f:
        f.write("geometry { union { shapes { rectangle { min { x: -1.5 y: -0.5 } max { x: -0.5 y: 0.5 } } }\n"
                "  shapes { rectangle { min { x: -0.6 y: -0.05 } max { x: 0.6 y: 0.05 } } }\n"
                "  shapes { rectangle { min { x: 0.5 y: -0.5 } max { x: 1.5 y: 0.5 } } } } }\n"
                "h0: 0.1\n")
    plain = summary_nodes(c.expect(OK, "generate", "dumbbell.textproto").stdout)
    featured = summary_nodes(c.expect(OK, "generate", "dumbbell.textproto",
                                      "--feature", "4,0.1,1", "--gradation", "0.3").stdout)
    assert featured > 1.3 * plain, f"{featured} nodes with --feature, {plain} without"
    print(f"  dumbbell: {plain} nodes, with --feature 4,0.1,1 {featured}")
    r = c.expect(BAD_REQUEST, "generate", "dumbbell.textproto", "--feature", "0,0.1,1")
    assert "size.terms[0].feature.elements" in r.stderr and "[1, 1000]" in r.stderr, r.stderr
    r = c.expect(BAD_REQUEST, "generate", "dumbbell.textproto", "--feature", "4,0.1")
    assert "--feature:" in r.stderr and "elements,h_min,h_max" in r.stderr, r.stderr


def test_volume(c):
    """A 3D request from a file and from --sphere: tetrahedra in every 3D format, read back."""
    r = c.expect(OK, "generate", c.example("volumes/box_minus_sphere.textproto"), "-o", "v.msh",
                 "-o", "v.msh22", "-o", "v.vtu", "--deadline", "120")
    m = re.search(r"nodes (\d+)\s+tetrahedra (\d+)", r.stdout)
    assert m, f"no 3D summary in:\n{r.stdout}"
    nodes, tets = int(m.group(1)), int(m.group(2))
    assert "dihedral angles" in r.stdout, r.stdout
    try:
        import meshio
    except ImportError:
        meshio = None
    if meshio:
        for name in ("v.msh", "v.msh22", "v.vtu"):
            with contextlib.redirect_stdout(io.StringIO()):
                mesh = meshio.read(c.path(name), file_format="gmsh" if name.endswith("22")
                                   else None)
            read = sum(len(b.data) for b in mesh.cells if b.type == "tetra")
            assert (len(mesh.points), read) == (nodes, tets), f"{name}: {len(mesh.points)}, {read}"
    r = c.expect(OK, "generate", "--sphere", "1", "--hole", "0.4", "--h0", "0.3", "-o", "s.vtu")
    assert "tetrahedra" in r.stdout, r.stdout
    # 3D runs on the CPU engine only; its SVG is a picture of the surface.
    c.expect(FAILED_PRECONDITION, "generate", "--sphere", "1", "--h0", "0.3", "--backend", "gpu")
    c.expect(OK, "generate", "--sphere", "1", "--h0", "0.3", "-o", "s.svg")
    with open(c.path("s.svg")) as f:
        assert "<svg" in f.read(512), "s.svg is no SVG"
    # A volume's frames: a picture of each snapshot's surface.
    r = c.expect(OK, "generate", "--sphere", "1", "--h0", "0.3", "--frames", "vframes",
                 "--snapshot-every", "5")
    frames = sorted(os.listdir(c.path("vframes")))
    assert frames and f"wrote {len(frames)} frames" in r.stdout, (frames, r.stdout)
    with open(c.path(os.path.join("vframes", frames[0]))) as f:
        assert "<path" in f.read(), f"{frames[0]} draws no face"
    c.expect(BAD_REQUEST, "generate", "--sphere", "1", "--circle", "1", "--h0", "0.3")
    print(f"  {nodes} nodes, {tets} tetrahedra; read back by meshio: {bool(meshio)}")


def test_help(c):
    for argv, wanted in ((["--help"], "examples"), (["help", "generate"], "Examples:")):
        r = subprocess.run([c.meshctl_bin, *argv], capture_output=True, text=True, timeout=30)
        assert r.returncode == OK, f"meshctl {' '.join(argv)}: exit {r.returncode}"
        assert wanted in r.stdout, f"meshctl {' '.join(argv)} does not mention {wanted}"
    assert "meshctl generate examples/" in r.stdout, r.stdout


def test_not_serving_while_draining(c):
    # A meshd of its own: SIGTERM with a job running turns health NOT_SERVING (10) and refuses
    # new jobs (3) while it drains; cancelling the job lets it exit 0.
    with MeshdChild(c.meshd_bin, "--drain-timeout", "60") as meshd:
        job_id = c.expect(OK, "submit", c.long, server=meshd.address).stdout.strip()
        c.wait_state(job_id, "RUNNING", server=meshd.address)
        meshd.proc.send_signal(signal.SIGTERM)
        deadline = time.monotonic() + 10
        while c.run("health", "--deadline", "2", server=meshd.address).returncode != NOT_SERVING:
            assert time.monotonic() < deadline, "health never became NOT_SERVING"
            time.sleep(0.05)
        c.expect(UNAVAILABLE, "generate", "--circle", "1", "--h0", "0.1", server=meshd.address)
        c.expect(OK, "cancel", job_id, server=meshd.address)
        assert meshd.proc.wait(timeout=30) == 0, f"meshd exited {meshd.proc.returncode}"


TESTS = [test_health, test_generate_files, test_generate_json, test_frames, test_bad_request,
         test_gpu_on_cpu_server, test_too_large, test_submit_watch_status_list,
         test_queue_full_and_cancel, test_deadline, test_unreachable, test_command_line,
         test_output_file_error, test_import, test_request, test_sdf_grid, test_size_grid,
         test_feature, test_volume,
         test_help, test_not_serving_while_draining]


def main():
    parser = argparse.ArgumentParser()
    for flag in ("--meshd", "--meshctl", "--examples"):
        parser.add_argument(flag, required=True)
    args = parser.parse_args()
    # meshctl runs in a temporary folder (its -o files land there).
    args.meshd, args.meshctl, args.examples = map(os.path.abspath,
                                                  (args.meshd, args.meshctl, args.examples))
    failures = []
    with MeshdChild(args.meshd, "--queue-capacity", "2") as meshd, \
            tempfile.TemporaryDirectory() as tmp:
        c = Context(args, meshd.address, tmp)
        for test in TESTS:
            t = time.monotonic()
            try:
                test(c)
                print(f"PASS {test.__name__} ({time.monotonic() - t:.1f} s)", flush=True)
            except (AssertionError, subprocess.TimeoutExpired) as e:
                failures.append(test.__name__)
                print(f"FAIL {test.__name__}: {e}", flush=True)
        if failures:
            print(f"meshd's log:\n  {meshd.log()}")
    print(f"{len(failures)} of {len(TESTS)} sub-tests failed: {' '.join(failures)}" if failures
          else f"all {len(TESTS)} sub-tests passed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
