#!/usr/bin/env python3
"""The installed meshd package against a real meshd: meshes as arrays and files, snapshots,
submit, watch, jobs, the asyncio client, the progress reporters and examples/python/plate.py.

    client_checks.py --meshd BIN --tmp DIR --plate PLATE.py
        (run with the interpreter the package is installed in)
"""

import asyncio
import contextlib
import io
import math
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from check_runner import Skip  # noqa: E402
from client_helpers import (TIMEOUT_S, check_ring, expect_async, main, ring)  # noqa: E402

import numpy as np  # noqa: E402

import meshd  # noqa: E402


def test_generate(ctx):
    seen = []
    mesh = ctx.client.generate(ring(), progress=seen.append)
    check_ring(mesh)
    kinds = [type(e).__name__ for e in seen]
    assert kinds[0] == "Queued" and "Started" in kinds and kinds[-1] == "Done", kinds
    assert seen[-1].mesh is mesh and mesh.job_id == seen[0].job_id
    text = io.StringIO()
    with contextlib.redirect_stderr(text):
        ctx.client.generate(ring(0.2), progress="text")
    assert "started on" in text.getvalue() and "done: " in text.getvalue(), text.getvalue()


def test_distance_grid(ctx):
    """A ring whose outside is a sampled disk (a numpy array), minus an exact hole: test_generate's
    ring, its outer nodes on the circle to the interpolation error (h^2 / 4 at radius 1)."""
    h = 0.025
    y, x = np.mgrid[0:97, 0:97] * h - 1.2
    disk = meshd.distance_grid(np.hypot(x, y) - 1, spacing=h, origin=(-1.2, -1.2))
    mesh = ctx.client.generate(meshd.request(disk.named("outer") - meshd.circle(0.3).named("hole"),
                                             h0=0.1, backend="cpu"))
    exact = math.pi * (1 - 0.3 ** 2)
    assert abs(mesh.areas().sum() - exact) < 0.02 * exact, f"area {mesh.areas().sum()}"
    assert sorted(mesh.boundary_names) == ["hole", "outer"], mesh.boundary_names
    outer = np.unique(mesh.boundary_groups["outer"])
    r = np.hypot(*mesh.points[outer].T)
    assert len(outer) > 10 and np.allclose(r, 1, atol=h * h / 4), f"outer nodes at radii {r}"


def test_volume(ctx):
    """A cube minus a ball through the real meshd (about 800 nodes): the Done event's TetMesh,
    whose tetrahedra are positive and fill the volume, its groups, its files read back by meshio
    (.vtu and .msh); the volume's own errors."""
    part = meshd.box((-1, -1, -1), (1, 1, 1), name="box") - meshd.sphere(0.5, name="ball")
    events = list(ctx.client.stream(meshd.request(part, h0=0.25)))
    assert isinstance(events[-1], meshd.Done), [type(e).__name__ for e in events]
    mesh = events[-1].mesh
    assert isinstance(mesh, meshd.TetMesh), type(mesh)
    n, m, f = len(mesh.points), len(mesh.tetrahedra), len(mesh.boundary_faces)
    assert 500 < n < 2000, f"{n} nodes for the cube minus a ball at h0 0.25"
    assert mesh.points.shape == (n, 3) and mesh.points.dtype == np.float64, mesh.points.dtype
    assert mesh.tetrahedra.shape == (m, 4) and mesh.tetrahedra.dtype == np.int32, mesh
    assert mesh.boundary_faces.shape == (f, 3) and mesh.boundary_tags.shape == (f,), mesh
    assert 0 <= mesh.tetrahedra.min() and mesh.tetrahedra.max() < n, "index out of range"
    # Volumes computed here, not with the package: (b - a) . ((c - a) x (d - a)) / 6.
    p = mesh.points[mesh.tetrahedra]
    volumes = np.einsum("ij,ij->i", p[:, 1] - p[:, 0],
                        np.cross(p[:, 2] - p[:, 0], p[:, 3] - p[:, 0])) / 6
    exact = 8 - 4 / 3 * math.pi * 0.5 ** 3
    assert volumes.min() > 0 and abs(volumes.sum() - exact) < 0.02 * exact, volumes.sum()
    assert np.allclose(mesh.volumes(), volumes, rtol=1e-12, atol=0)
    assert abs(mesh.quality.volume - volumes.sum()) < 1e-9 * exact, mesh.quality
    assert mesh.quality.min_dihedral_deg > 10 and mesh.quality.q_min > 0.2, mesh.quality
    assert mesh.quality.min_dihedral_deg < 70.53 < mesh.quality.max_dihedral_deg < 180
    # The surface's nodes on the cube or the sphere within 1e-3 h0, by the exact distance here.
    s = mesh.points[np.unique(mesh.boundary_faces)]
    off = np.maximum(np.abs(s).max(axis=1) - 1, 0.5 - np.linalg.norm(s, axis=1))
    assert np.abs(off).max() < 1e-3 * 0.25, np.abs(off).max()
    assert abs(mesh.quality.max_surface_offset - np.abs(off).max()) < 1e-9, mesh.quality
    assert abs(mesh.tetrahedron_quality().min() - mesh.quality.q_min) < 1e-9, mesh.quality
    assert sum(mesh.quality.histogram) == m, mesh.quality.histogram
    assert mesh.backend == "cpu" and mesh.stats.fixed_nodes > 8, (mesh.backend, mesh.stats)
    assert mesh.stats.iterations > 0 and mesh.stats.t_slivers >= 0, mesh.stats
    assert sorted(mesh.boundary_groups) == ["ball", "box"], mesh.boundary_names
    # Each group's faces lie nearer its own surface (by their centroids: at this coarse h0 a few
    # faces reach a node inside, and the ball is only 2 h0 across).
    for name, faces in mesh.boundary_groups.items():
        centroids = mesh.points[faces].mean(axis=1)
        nearer_box = 1 - np.abs(centroids).max(axis=1) < np.linalg.norm(centroids, axis=1) - 0.5
        assert len(faces) > 12 and nearer_box.all() == (name == "box") == nearer_box.any(), name
    try:
        import meshio
    except ImportError:
        meshio = None
    if meshio:
        for name in ("part.vtu", "part.msh"):
            path = os.path.join(ctx.tmp, name)
            mesh.write(path)
            back = meshio.read(path)
            # The same tetrahedra by their corners: meshio's MSH writer reorders nodes.
            tets = np.concatenate([c.data for c in back.cells if c.type == "tetra"])
            assert len(back.points) == n and same_rows(
                back.points[tets].reshape(-1, 12), mesh.points[mesh.tetrahedra].reshape(-1, 12)), \
                f"{name}: tetrahedra differ"
            faces = sum(len(c.data) for c in back.cells if c.type == "triangle")
            assert faces == f, f"{name}: {faces} boundary triangles"
        groups = {k: tuple(v) for k, v in back.field_data.items()}
        tag = {name: i + 2 for i, name in enumerate(mesh.boundary_names)}
        assert groups == {"domain": (1, 3), "box": (tag["box"], 2), "ball": (tag["ball"], 2)}, \
            groups
        physical = np.concatenate([t for c, t in zip(back.cells, back.cell_data["gmsh:physical"])
                                   if c.type == "triangle"])
        counts = {name: int((physical == tag[name]).sum()) for name in tag}
        assert counts == {k: len(v) for k, v in mesh.boundary_groups.items()}, counts
    try:
        ctx.client.generate(meshd.request(part, h0=0.25, backend="gpu"))
        raise AssertionError("BACKEND_GPU ran on a server without a GPU")
    except meshd.FailedPrecondition:
        pass
    try:
        ctx.client.generate(meshd.request(meshd.sphere(-1), h0=0.25))
        raise AssertionError("a negative radius was accepted")
    except meshd.InvalidArgument as e:
        assert "volume.geometry.sphere.radius" in str(e), e
        assert e.field == "volume.geometry.sphere.radius", e.field
    # A volume's snapshots: the nodes #N by 3 and the tetrahedra, the first one carrying them.
    events = list(ctx.client.stream(meshd.request(part, h0=0.25, snapshot_every=5)))
    snapshots = [e for e in events if isinstance(e, meshd.Snapshot)]
    assert snapshots and snapshots[0].topology_changed, [type(e).__name__ for e in events]
    for s in snapshots:
        assert s.iteration % 5 == 0 and s.triangles is None, s.iteration
        assert s.points.ndim == 2 and s.points.shape[1] == 3, s.points.shape
        assert s.tetrahedra.shape[1] == 4 and s.tetrahedra.max() < len(s.points), s.iteration
    assert isinstance(events[-1], meshd.Done) and len(events[-1].mesh.tetrahedra) > 0


def test_polyhedron(ctx):
    """A solid given by its triangle surface (the cube as 12 triangles, given inward) minus a ball,
    through the real meshd: the same volume as the box's, its surface on the cube or the ball; an
    open surface refused, naming its field."""
    corners = np.array([[x, y, z] for z in (-1, 1) for y in (-1, 1) for x in (-1, 1)], float)
    outward = np.array([[0, 2, 3], [0, 3, 1], [4, 5, 7], [4, 7, 6], [0, 1, 5], [0, 5, 4],
                        [2, 6, 7], [2, 7, 3], [0, 4, 6], [0, 6, 2], [1, 3, 7], [1, 7, 5]])
    inward = outward[:, [0, 2, 1]]
    part = meshd.polyhedron(corners, inward, name="box") - meshd.sphere(0.5, name="ball")
    mesh = ctx.client.generate(meshd.request(part, h0=0.25))
    assert isinstance(mesh, meshd.TetMesh) and sorted(mesh.boundary_groups) == ["ball", "box"]
    exact = 8 - 4 / 3 * math.pi * 0.5 ** 3
    assert abs(mesh.volumes().sum() - exact) < 0.02 * exact and mesh.volumes().min() > 0
    s = mesh.points[np.unique(mesh.boundary_faces)]
    off = np.maximum(np.abs(s).max(axis=1) - 1, 0.5 - np.linalg.norm(s, axis=1))
    assert np.abs(off).max() < 1e-3 * 0.25, np.abs(off).max()
    try:
        ctx.client.generate(meshd.request(meshd.polyhedron(corners, outward[:-1]), h0=0.25))
        raise AssertionError("an open surface was accepted")
    except meshd.InvalidArgument as e:
        assert e.field == "volume.geometry.polyhedron.triangles" and "closed" in str(e), e
    try:
        meshd.polyhedron(corners, [[0, 1, 8]])
        raise AssertionError("an index out of range was accepted")
    except ValueError as e:
        assert "[0, 8)" in str(e), e


def same_rows(a, b):
    """Whether a and b hold the same rows in any order (to 1e-12)."""
    order = lambda x: x[np.lexsort(x.T[::-1])]  # noqa: E731
    return a.shape == b.shape and np.allclose(order(a), order(b), rtol=0, atol=1e-12)


def test_to_meshio(ctx):
    try:
        import meshio
    except ImportError:
        raise Skip("no meshio (python3-meshio)")
    mesh = ctx.client.generate(ring())
    for name in ("ring.vtu", "ring.msh"):
        path = os.path.join(ctx.tmp, name)
        mesh.write(path)
        back = meshio.read(path)
        # The same triangles, compared by their corners: meshio's MSH writer reorders nodes.
        triangles = np.concatenate([c.data for c in back.cells if c.type == "triangle"])
        assert same_rows(back.points[triangles, :2].reshape(-1, 6),
                         mesh.points[mesh.triangles].reshape(-1, 6)), f"{name}: triangles differ"
        assert len(back.points) == len(mesh.points), f"{name}: {len(back.points)} nodes"
        lines = sum(len(c.data) for c in back.cells if c.type == "line")
        assert lines == len(mesh.boundary_edges), f"{name}: {lines} boundary lines"
    groups = {k: tuple(v) for k, v in back.field_data.items()}
    assert groups == {"domain": (1, 2), "outer": (2, 1), "hole": (3, 1)} or \
        groups == {"domain": (1, 2), "outer": (3, 1), "hole": (2, 1)}, groups
    # Each group's lines keep its physical tag in the .msh (a cell block per group).
    physical = np.concatenate([t for c, t in zip(back.cells, back.cell_data["gmsh:physical"])
                               if c.type == "line"])
    counts = {name: int((physical == groups[name][0]).sum()) for name in ("outer", "hole")}
    assert counts == {k: len(v) for k, v in mesh.boundary_groups.items()}, counts


def check_snapshots(events):
    snapshots = [e for e in events if isinstance(e, meshd.Snapshot)]
    for s in snapshots:
        assert s.points.ndim == 2 and s.points.shape[1] == 2, s.points.shape
        assert s.triangles is not None, f"snapshot {s.iteration} before any triangles"
        assert s.triangles.max() < len(s.points), f"snapshot {s.iteration}: index out of range"
    assert not snapshots or snapshots[0].topology_changed, "the first snapshot has no triangles"
    return snapshots


def test_snapshots(ctx):
    # Snapshots reach a stream only while its job runs: an 8,000-node ring meshes for hundreds
    # of iterations, each publishing one.
    events = list(ctx.client.stream(ring(0.02, snapshot_every=1)))
    assert len(check_snapshots(events)) > 0, [type(e).__name__ for e in events]
    assert isinstance(events[-1], meshd.Done) and len(events[-1].mesh.points) > 5000


def test_submit_watch_jobs(ctx):
    job_id = ctx.client.submit(ring(snapshot_every=5, label="package"))
    events = list(ctx.client.watch(job_id))
    kinds = [type(e).__name__ for e in events]
    # A job that finished before Watch began streams queued, started and done alone.
    assert kinds[0] == "Queued" and "Started" in kinds and kinds[-1] == "Done", kinds
    assert {e.job_id for e in events} == {job_id}
    check_snapshots(events)
    mesh = events[-1].mesh
    check_ring(mesh)
    again = ctx.client.result(job_id)  # a finished job's result, at once
    assert (again.points == mesh.points).all() and (again.triangles == mesh.triangles).all()
    info = ctx.client.job(job_id)
    assert (info.state, info.label, info.error) == ("succeeded", "package", None), info
    assert info.quality == mesh.quality and info.nodes == len(mesh.points), info
    assert job_id in [j.job_id for j in ctx.client.jobs()]
    assert job_id in [j.job_id for j in ctx.client.jobs("succeeded")]
    assert job_id not in [j.job_id for j in ctx.client.jobs("cancelled")]


def test_aio(ctx):
    async def run():
        async with meshd.aio.Client(ctx.address, timeout=TIMEOUT_S) as client:
            check_ring(await client.generate(ring()))
            job_id = await client.submit(ring())
            kinds = [type(e).__name__ async for e in client.watch(job_id)]
            assert kinds[0] == "Queued" and kinds[-1] == "Done", kinds
            assert (await client.job(job_id)).state == "succeeded"
            assert job_id in [j.job_id for j in await client.jobs("succeeded")]
            check_ring(await client.result(job_id))
            e = await expect_async(meshd.NotFound, client.job("no-such-job"))
            assert e.field == "job_id", e.field
            e = await expect_async(meshd.InvalidArgument, client.generate(ring(h0=-1)))
            assert e.field == "h0", e.field
    asyncio.run(run())


def test_optional_reporters(ctx):
    """tqdm's bar and the live plot, where tqdm, matplotlib and IPython are installed."""
    available = []
    with contextlib.redirect_stderr(io.StringIO()) as text:
        try:
            ctx.client.generate(ring(), progress="tqdm")
            assert "100%" in text.getvalue(), text.getvalue()
            available.append("tqdm")
        except ImportError:
            pass
    try:
        os.environ.setdefault("MPLBACKEND", "Agg")
        from meshd.live_plot import LivePlot
        with contextlib.redirect_stdout(io.StringIO()):  # outside Jupyter, display() prints
            plot = LivePlot()
            mesh = ctx.client.generate(ring(0.05, snapshot_every=10), progress=plot)
        assert plot.ax.get_title().startswith(f"{len(mesh.points)} nodes"), plot.ax.get_title()
        assert len(plot.ax.lines) > 0, "nothing drawn"
        available.append("live plot")
    except ImportError:
        pass
    if not available:
        raise Skip("neither tqdm nor matplotlib with IPython is installed")
    print(f"  checked: {', '.join(available)}")


def test_plate_example(ctx):
    """examples/python/plate.py, run as a user would: a file with its groups, and a bad h0."""
    try:
        import meshio
    except ImportError:
        raise Skip("no meshio (python3-meshio)")
    out = os.path.join(ctx.tmp, "plate.msh")
    command = [sys.executable, ctx.plate, "--server", ctx.address, "--deadline", str(TIMEOUT_S)]
    r = subprocess.run(command + ["--h0", "0.08", out], capture_output=True, text=True,
                       timeout=TIMEOUT_S)
    assert r.returncode == 0 and "wrote " in r.stdout, f"exit {r.returncode}\n{r.stderr}"
    back = meshio.read(out)
    assert {"plate", "holes", "domain"} <= set(back.field_data), back.field_data
    r = subprocess.run(command + ["--h0", "-1", out + ".bad"], capture_output=True, text=True,
                       timeout=TIMEOUT_S)
    assert r.returncode == 1 and "(field h0)" in r.stderr, f"exit {r.returncode}\n{r.stderr}"
    assert not os.path.exists(out + ".bad"), "a failed request wrote its output"


def test_pulley_example(ctx):
    """examples/python/pulley.py, beside plate.py: tetrahedra in a file meshio reads."""
    try:
        import meshio
    except ImportError:
        raise Skip("no meshio (python3-meshio)")
    out = os.path.join(ctx.tmp, "pulley.vtu")
    pulley = os.path.join(os.path.dirname(ctx.plate), "pulley.py")
    r = subprocess.run([sys.executable, pulley, "--server", ctx.address, "--deadline",
                        str(TIMEOUT_S), "--h0", "0.12", out], capture_output=True, text=True,
                       timeout=TIMEOUT_S)
    assert r.returncode == 0 and "wrote " in r.stdout, f"exit {r.returncode}\n{r.stderr}"
    back = meshio.read(out)
    assert sum(len(c.data) for c in back.cells if c.type == "tetra") > 0, back


if __name__ == "__main__":
    sys.exit(main([test_generate, test_distance_grid, test_volume, test_polyhedron, test_to_meshio,
                   test_snapshots,
                   test_submit_watch_jobs, test_aio, test_optional_reporters, test_plate_example,
                   test_pulley_example],
                  "--plate"))
