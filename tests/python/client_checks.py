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
    """A cube minus a ball through the real meshd: a TetMesh whose tetrahedra are positive and
    fill the volume, its groups, its file read back; the volume's own errors."""
    part = meshd.box((-1, -1, -1), (1, 1, 1), name="box") - meshd.sphere(0.5, name="ball")
    mesh = ctx.client.generate(meshd.request(part, h0=0.25))
    assert isinstance(mesh, meshd.TetMesh), type(mesh)
    assert mesh.points.shape[1] == 3 and mesh.tetrahedra.shape[1] == 4, mesh
    assert mesh.boundary_faces.shape == (len(mesh.boundary_tags), 3), mesh
    volumes = mesh.volumes()
    exact = 8 - 4 / 3 * math.pi * 0.5 ** 3
    assert volumes.min() > 0 and abs(volumes.sum() - exact) < 0.02 * exact, volumes.sum()
    assert abs(mesh.quality.volume - volumes.sum()) < 1e-9 * exact, mesh.quality
    assert mesh.quality.min_dihedral_deg > 10 and mesh.quality.q_min > 0.2, mesh.quality
    assert mesh.backend == "cpu" and mesh.stats.fixed_nodes > 8, (mesh.backend, mesh.stats)
    assert sorted(mesh.boundary_groups) == ["ball", "box"], mesh.boundary_names
    try:
        import meshio
    except ImportError:
        meshio = None
    if meshio:
        path = os.path.join(ctx.tmp, "part.msh")
        mesh.write(path)
        back = meshio.read(path)
        tets = sum(len(c.data) for c in back.cells if c.type == "tetra")
        assert (len(back.points), tets) == (len(mesh.points), len(mesh.tetrahedra)), back
        assert {"domain", "box", "ball"} <= set(back.field_data), back.field_data
    try:
        ctx.client.generate(meshd.request(part, h0=0.25, backend="gpu"))
        raise AssertionError("a volume ran on BACKEND_GPU")
    except meshd.FailedPrecondition:
        pass
    try:
        ctx.client.generate(meshd.request(meshd.sphere(-1), h0=0.25))
        raise AssertionError("a negative radius was accepted")
    except meshd.InvalidArgument as e:
        assert "volume.geometry.sphere.radius" in str(e), e


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
    sys.exit(main([test_generate, test_distance_grid, test_volume, test_to_meshio, test_snapshots,
                   test_submit_watch_jobs, test_aio, test_optional_reporters, test_plate_example,
                   test_pulley_example],
                  "--plate"))
