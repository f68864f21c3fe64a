#!/usr/bin/env python3
"""A reader far slower than its job: meshd's memory stays flat, and the stream goes on.

    slow_reader.py --meshd BIN --python-stubs DIR [--sleep 8] [--rss-bound-mb 100]

Starts BIN (--backend cpu, metrics on) and a Generate of a ~40,000-node disk with a snapshot
every iteration and a tolerance it never reaches within max_iterations 3000: it streams a
~1.3 MB snapshot per iteration. The client reads one event, then sleeps while sampling meshd's
RSS every 0.5 s: the server must not queue the snapshots it cannot send (service.proto: "a slow
reader gets the latest ones"). Then it reads on: events still come, the snapshots it gets skip
the iterations it missed, and cancelling the call ends the stream CANCELLED and the job with it.
Exit status: 0 when all hold, 1 otherwise, 77 when grpcio is missing.
"""

import argparse
import hashlib
import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import meshd_launcher as ml  # noqa: E402

RPC_TIMEOUT = 120
H0_40K = 0.0095  # unit disk: 1.155 pi / h0^2 = 40,200 nodes
NODES_40K = 40200
MAX_SLEEP = 60  # s: the longest stall, on a slow machine


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--meshd", required=True, help="the meshd executable")
    parser.add_argument("--python-stubs", required=True, help="<build>/python (meshd.v1 stubs)")
    parser.add_argument("--sleep", type=float, default=8, help="seconds the reader stalls")
    # What a server that holds one snapshot per stream may add while its reader stalls: the
    # running job itself (40k nodes: points, triangulation, forces, ~20 MB), the job's latest
    # snapshot plus the stream's copy in its message (2 x ~1.6 MB), that message serialized into
    # the transport (~1.6 MB, again when gRPC slices it) and HTTP/2 flow-control windows (a few
    # MB at most once BDP probing has grown them): some 30 MB, and 100 MB leaves the allocator
    # its slack. A server that queued every snapshot would pass 100 MB within ~75 iterations.
    parser.add_argument("--rss-bound-mb", type=float, default=100)
    args = parser.parse_args()
    if ml.import_grpc(args.python_stubs) is None:
        return ml.SKIP

    meshd = ml.Meshd(args.meshd)
    channel = ml.grpc.insecure_channel(meshd.address)
    stub = ml.service_pb2_grpc.MeshServiceStub(channel)
    S, problems = ml.service_pb2, []
    try:
        request = ml.disk(H0_40K)
        request.options.snapshot_every = 1
        request.params.dptol = 1e-9
        request.params.max_iterations = 3000
        rss_start = meshd.rss_mb()
        call = stub.Generate(request, timeout=RPC_TIMEOUT)
        first = next(call)
        job = S.JobRef(job_id=first.job_id)
        print(f"meshd on port {meshd.port}: RSS {rss_start:.1f} MB; job {first.job_id} "
              f"streaming, first event {first.WhichOneof('event')}; the reader sleeps", flush=True)

        # Stall for --sleep s, and on a slow machine until the job has run enough iterations
        # that a server queueing their snapshots would hold twice the bound (counting only the
        # points, 16 bytes a node), so that the bound can tell the two apart.
        enough = 2 * args.rss_bound_mb * 2 ** 20 / (16 * NODES_40K)
        samples, info, t0 = [], S.JobInfo(), time.monotonic()
        while time.monotonic() - t0 < args.sleep or (
                info.iteration < enough and time.monotonic() - t0 < MAX_SLEEP and
                info.state == S.JOB_STATE_RUNNING):
            samples.append(meshd.rss_mb())
            time.sleep(0.5)
            info = stub.GetJob(job, timeout=RPC_TIMEOUT)
        iterations, slept = info.iteration, time.monotonic() - t0
        peak = max(samples)
        print(f"RSS while the reader slept {slept:.1f} s ({iterations} iterations): start "
              f"{rss_start:.1f} MB, peak {peak:.1f} MB ({peak - rss_start:+.1f} MB; bound "
              f"{args.rss_bound_mb:.0f} MB); samples " + " ".join(f"{s:.0f}" for s in samples))
        if peak > rss_start + args.rss_bound_mb:
            ml.rss_problem(problems, f"RSS grew by {peak - rss_start:.1f} MB while the reader slept")
        if iterations < enough and info.state == S.JOB_STATE_RUNNING:
            problems.append(f"inconclusive: only {iterations} iterations in {slept:.0f} s")

        # Read on: events come at once, and 20 snapshots later the call is cancelled (or, on a
        # machine fast enough to finish 3000 iterations during the stall, the result comes).
        snapshots, sizes, chunks, done, code = [], [], [], None, "OK"
        try:
            for event in call:
                if event.HasField("snapshot"):
                    snapshots.append(event.snapshot.iteration)
                    sizes.append(event.ByteSize())
                    if len(snapshots) == 20:
                        call.cancel()
                elif event.HasField("result_chunk"):
                    chunks.append(event.result_chunk.data)
                elif event.HasField("done"):
                    done = event.done
        except ml.grpc.RpcError as e:
            code = e.code().name
        print(f"read on: {len(snapshots)} snapshots, iterations {snapshots[:4]} ... "
              f"{snapshots[-1:]}; the stream ended {code}")
        if code == "CANCELLED":
            # The first ones may be what sat in the transport's buffers; then they must jump to
            # the present, having skipped what was missed (a backlog would go 1, 2, 3, ...).
            want = S.JOB_STATE_CANCELLED
            if not snapshots or snapshots[-1] < iterations or len(snapshots) >= snapshots[-1]:
                problems.append(f"snapshots {snapshots} never reached iteration {iterations}, "
                                f"where the job was when the stall ended: a backlog?")
        else:
            want = S.JOB_STATE_SUCCEEDED
            if code != "OK" or done is None or \
                    hashlib.sha256(b"".join(chunks)).hexdigest() != done.result_sha256:
                problems.append(f"the stream ended {code} without a verified result")

        # What buffering every snapshot would have cost, at the sizes the stream carried: the
        # points alone, or with the triangles when the topology changed.
        lo, hi = min(sizes, default=0) / 2 ** 20, max(sizes, default=0) / 2 ** 20
        print(f"snapshots of {lo:.2f}-{hi:.2f} MB: a server that buffered every one would have "
              f"held {iterations * lo:.0f}-{iterations * hi:.0f} MB at the end of the stall, "
              f"and {request.params.max_iterations * lo:.0f} MB or more for the whole job")

        ml.wait_for(f"the job to be {S.JobState.Name(want)}",
                    lambda: stub.GetJob(job, timeout=RPC_TIMEOUT).state == want, 10)
        ml.wait_for("meshd_live_jobs and meshd_active_streams to return to 0",
                    lambda: meshd.metric("meshd_live_jobs") == 0 and
                    meshd.metric("meshd_active_streams") == 0, 10)
        channel.close()
        code = meshd.stop()
        if code != 0:
            problems.append(f"meshd exited {code} after SIGTERM")
    except AssertionError as e:
        problems.append(str(e))
    finally:
        meshd.kill()
    for p in problems:
        print(f"PROBLEM: {p}")
    if problems:
        print("  meshd's log (tail):\n    " + meshd.log_tail())
    print("FAIL" if problems else "PASS")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
