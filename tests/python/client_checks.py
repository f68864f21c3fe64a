#!/usr/bin/env python3
"""The installed meshd package against a real meshd: meshes as arrays and files, submit, watch,
cancel, jobs, the asyncio client, the bearer token, and a failure of each kind.

    client_checks.py --meshd BIN --tmp DIR   (run with the interpreter the package is installed in)

Starts `BIN --listen 127.0.0.1:0 --backend cpu --cpu-workers 2 --cpu-threads 1` (and a second
one with --token-file for the token check). Every assertion is about what comes back, never
about how long it took.
"""

import argparse
import asyncio
import contextlib
import io
import math
import os
import socket
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(HERE, os.pardir, "client"))
from check_runner import Skip, run_checks  # noqa: E402
from meshd_child import MeshdChild  # noqa: E402

import numpy as np  # noqa: E402

import meshd  # noqa: E402

TIMEOUT_S = 120  # every call's deadline: a hang fails instead of blocking
# A disk of about 226,000 nodes: far more than any machine meshes within SHORT_DEADLINE_S on
# two CPU threads, so that a deadline or a cancel always lands while it runs.
BIG = meshd.request(meshd.circle(1), h0=0.004, backend="cpu")
SHORT_DEADLINE_S = 0.2


def ring(h0=0.1, **options):
    """A ring with named boundary groups: outer radius 1, hole radius 0.3."""
    shape = meshd.circle(1).named("outer") - meshd.circle(0.3).named("hole")
    return meshd.request(shape, h0=h0, backend="cpu", **options)


def check_ring(mesh):
    n, m = len(mesh.points), len(mesh.triangles)
    assert mesh.points.shape == (n, 2) and mesh.points.dtype == np.float64 and n > 100
    assert mesh.triangles.shape == (m, 3) and m > n, mesh
    assert mesh.triangles.min() >= 0 and mesh.triangles.max() < n, "triangle index out of range"
    areas = mesh.areas()
    assert (areas > 0).all(), f"{(areas <= 0).sum()} triangles with area <= 0"
    # Both boundaries are inscribed polygons: the outer one loses area, the hole gives some back.
    exact = math.pi * (1 - 0.3 ** 2)
    assert abs(areas.sum() - exact) < 0.02 * exact, f"area {areas.sum()}, ring {exact}"
    assert sorted(mesh.boundary_names) == ["hole", "outer"], mesh.boundary_names
    for name, radius in (("outer", 1.0), ("hole", 0.3)):
        edges = mesh.boundary_groups[name]
        r = np.linalg.norm(mesh.points[edges.ravel()], axis=1)
        assert len(edges) > 10 and np.allclose(r, radius, atol=1e-6), f"{name} off its circle"
    assert abs(mesh.triangle_quality().min() - mesh.quality.q_min) < 1e-6, mesh.quality
    assert mesh.quality.q_min > 0.5 and mesh.stats.converged and mesh.backend == "cpu", mesh
    assert sum(mesh.quality.histogram) == m


def expect(error, call):
    """Runs call() and returns the exception of type error it raises; fails otherwise."""
    try:
        result = call()
    except error as e:
        assert isinstance(e, meshd.MeshdError) and e.code == error.code, e
        return e
    raise AssertionError(f"expected {error.__name__}, got {result!r}")


def wait_for_state(client, job_id, states):
    deadline = time.monotonic() + 60
    while (info := client.job(job_id)).state not in states:
        assert time.monotonic() < deadline, f"job {job_id} still {info.state}"
        time.sleep(0.05)
    return info


# ---- sub-tests ----------------------------------------------------------------------------------

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


async def expect_async(error, awaitable):
    """expect() for a coroutine."""
    try:
        result = await awaitable
    except error as e:
        assert e.code == error.code, e
        return e
    raise AssertionError(f"expected {error.__name__}, got {result!r}")


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


def test_invalid_argument(ctx):
    bad = meshd.request(meshd.circle(1) - meshd.circle(-0.5), h0=0.1, backend="cpu")
    for call in (lambda: ctx.client.generate(bad), lambda: ctx.client.submit(bad)):
        e = expect(meshd.InvalidArgument, call)
        assert e.field == "geometry.difference.subtract[0].circle.radius", e.field
        assert "> 0" in e.reason and e.field not in e.reason, e.reason
    e = expect(meshd.InvalidArgument, lambda: ctx.client.generate(ring(h0=-1)))
    assert e.field == "h0", e


def test_not_found(ctx):
    for call in (lambda: list(ctx.client.watch("no-such-job")),
                 lambda: ctx.client.cancel("no-such-job"), lambda: ctx.client.job("no-such-job")):
        e = expect(meshd.NotFound, call)
        assert e.field == "job_id" and "no-such-job" in e.reason, e


def test_unavailable(ctx):
    with socket.socket() as s:  # a port nothing listens on
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    with meshd.Client(f"127.0.0.1:{port}", timeout=TIMEOUT_S) as client:
        expect(meshd.Unavailable, lambda: client.generate(ring()))
        expect(meshd.Unavailable, lambda: client.jobs())


def test_unauthenticated(ctx):
    token_file = os.path.join(ctx.tmp, "token")
    with open(token_file, "w") as f:
        f.write("package-test-token\n")
    with MeshdChild(ctx.binary, "--token-file", token_file) as server:
        for token in ("", "wrong"):
            with meshd.Client(server.address, token=token, timeout=TIMEOUT_S) as client:
                expect(meshd.Unauthenticated, lambda: client.jobs())
                expect(meshd.Unauthenticated, lambda: client.generate(ring()))
        with meshd.Client(server.address, token="package-test-token", timeout=TIMEOUT_S) as c:
            check_ring(c.generate(ring()))


def test_cancelled(ctx):
    job_id = ctx.client.submit(BIG)
    assert ctx.client.cancel(job_id).job_id == job_id
    e = expect(meshd.Cancelled, lambda: list(ctx.client.watch(job_id)))
    info = wait_for_state(ctx.client, job_id, ("cancelled", "failed", "succeeded"))
    assert info.state == "cancelled" and isinstance(info.error, meshd.Cancelled), info
    assert job_id in [j.job_id for j in ctx.client.jobs("cancelled")], e
    # Leaving a Generate stream early cancels its job too.
    stream = ctx.client.stream(BIG)
    started = next(e for e in stream if isinstance(e, meshd.Started))
    stream.close()
    info = wait_for_state(ctx.client, started.job_id, ("cancelled", "failed", "succeeded"))
    assert info.state == "cancelled", info


def test_deadline_exceeded(ctx):
    e = expect(meshd.DeadlineExceeded,
               lambda: ctx.client.generate(BIG, timeout=SHORT_DEADLINE_S))
    print(f"  {e}")
    # The server cancels a Generate job whose deadline passed; it stays up and meshes again.
    check_ring(ctx.client.generate(ring()))


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


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--meshd", required=True)
    parser.add_argument("--tmp", required=True)
    parser.add_argument("--plate", required=True, help="examples/python/plate.py")
    args = parser.parse_args()
    with MeshdChild(args.meshd, "--cpu-workers", "2", "--cpu-threads", "1") as server:
        ctx = argparse.Namespace(binary=args.meshd, tmp=args.tmp, address=server.address,
                                 plate=args.plate,
                                 client=meshd.Client(server.address, timeout=TIMEOUT_S))
        tests = [test_generate, test_to_meshio, test_snapshots, test_submit_watch_jobs, test_aio,
                 test_invalid_argument, test_not_found, test_unavailable, test_unauthenticated,
                 test_optional_reporters, test_plate_example, test_cancelled,
                 test_deadline_exceeded]
        status = run_checks(tests, ctx,
                            on_failure=lambda: print(f"  meshd's log:\n  {server.log()}"))
        ctx.client.close()
        return status


if __name__ == "__main__":
    sys.exit(main())
