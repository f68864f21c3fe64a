"""What the client check scripts share: the requests they send, the checks of a mesh, and a
main() that starts a meshd and runs sub-tests against it.

Every assertion is about what comes back, never about how long it took.
"""

import argparse
import math
import os
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, os.pardir, "client"))
from check_runner import run_checks  # noqa: E402
from meshd_child import MeshdChild  # noqa: E402

import numpy as np  # noqa: E402

import meshd  # noqa: E402

TIMEOUT_S = 120  # every call's deadline: a hang fails instead of blocking
# A disk of about 226,000 nodes: far more than any machine meshes within SHORT_DEADLINE_S on one
# CPU thread (the workers below), so that a deadline or a cancel always lands while it runs.
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

async def expect_async(error, awaitable):
    """expect() for a coroutine."""
    try:
        result = await awaitable
    except error as e:
        assert e.code == error.code, e
        return e
    raise AssertionError(f"expected {error.__name__}, got {result!r}")


def main(tests, *extra_flags):
    """Parses --meshd, --tmp and extra_flags, starts `meshd --backend cpu --cpu-workers 2
    --cpu-threads 1` and runs tests(ctx) against it; returns the exit status."""
    parser = argparse.ArgumentParser()
    for flag in ("--meshd", "--tmp", *extra_flags):
        parser.add_argument(flag, required=True)
    args = parser.parse_args()
    with MeshdChild(args.meshd, "--cpu-workers", "2", "--cpu-threads", "1") as server:
        ctx = argparse.Namespace(**vars(args), binary=args.meshd, address=server.address,
                                 client=meshd.Client(server.address, timeout=TIMEOUT_S))
        status = run_checks(tests, ctx,
                            on_failure=lambda: print(f"  meshd's log:\n  {server.log()}"))
        ctx.client.close()
        return status
