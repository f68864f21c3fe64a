#!/usr/bin/env python3
"""Clients that die mid-stream: meshd cancels what they owned and keeps no trace of them.

    crashing_clients.py --meshd BIN --python-stubs DIR [--iterations 40] [--seed 1]
                        [--rss-margin-mb 30]

Starts BIN (--backend cpu, metrics on), warms it up with a few jobs and records its RSS. Then,
each iteration, starts a child Python process that opens a stream and is killed with SIGKILL
at a random moment after its first event: a Generate of a ~10,000-node disk that never
converges, with a snapshot every iteration (the server is mid-write of a large message at
almost any moment), read as fast as the child can or not at all after the first event (the
transport's buffers full, a write pending), or a Watch of a job the parent submitted. A
process killed this way closes its socket without a word; the server must notice. Afterwards:
  - meshd_live_jobs and meshd_active_streams return to 0: every killed Generate's job is
    CANCELLED (it would run forever otherwise), every watched job SUCCEEDED (a Watch owns
    nothing);
  - the server still serves: a Generate succeeds;
  - RSS is within --rss-margin-mb of the warm RSS.
Exit status: 0 when all hold, 1 otherwise, 77 when grpcio is missing.
"""

import argparse
import os
import random
import signal
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import meshd_launcher as ml  # noqa: E402

RPC_TIMEOUT = 120
SETTLE_TIMEOUT = 60  # s: the submitted jobs still have to run after the last kill
H0_10K = 0.019  # unit disk: 1.155 pi / h0^2 = 10,000 nodes


def endless_generate():
    """~10,000 nodes, a snapshot every iteration, and a tolerance the nodes never reach: the
    job ends only when it is cancelled."""
    request = ml.disk(H0_10K)
    request.options.snapshot_every = 1
    request.params.dptol = 1e-9
    request.params.max_iterations = 1000000
    return request


def finite_job():
    """~10,000 nodes at the default tolerance: a few seconds at most on one core."""
    return ml.disk(H0_10K)


def child(args):
    """The client that will be killed: opens its stream, says which job it reads, reads on."""
    channel = ml.grpc.insecure_channel(args.server)
    stub = ml.service_pb2_grpc.MeshServiceStub(channel)
    if args.child in ("generate", "stalled"):
        call = stub.Generate(endless_generate(), timeout=RPC_TIMEOUT)
    else:
        call = stub.Watch(ml.service_pb2.JobRef(job_id=args.job_id), timeout=RPC_TIMEOUT)
    for n, event in enumerate(call):
        if n == 0:
            print(f"reading {event.job_id}", flush=True)
            if args.child == "stalled":
                time.sleep(RPC_TIMEOUT)
    return 0


def run_child(args, mode, job_id, rng):
    """Starts a child, waits for its first event, kills it at a random moment: its job id."""
    cmd = [sys.executable, os.path.abspath(__file__), "--child", mode, "--server", args.server,
           "--python-stubs", args.python_stubs, "--job-id", job_id]
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, text=True)
    try:
        line = proc.stdout.readline()  # blocks until the first event (or the child's death)
        if not line.startswith("reading "):
            raise AssertionError(f"child {mode} ended before its first event: {line!r}, "
                                 f"exit {proc.wait()}")
        # Mid-stream: snapshots are flowing (Generate) or the job is queued or running (Watch).
        time.sleep(rng.uniform(0.0, 1.0))
    finally:
        proc.send_signal(signal.SIGKILL)
        proc.wait()
    return line.split()[1]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--meshd", help="the meshd executable")
    parser.add_argument("--python-stubs", required=True, help="<build>/python (meshd.v1 stubs)")
    parser.add_argument("--iterations", type=int, default=40)
    parser.add_argument("--seed", type=int, default=1)
    # Growth beyond the retained results: allocator slack and gRPC's per-connection caches, a
    # few MB (measured: within +-2 MB). Leaked streams or jobs show in the gauges first; this
    # catches what they do not, e.g. one 10k-node snapshot (~0.4 MB) kept per killed Generate
    # (~10 MB over 40 iterations) or a job's arrays (several MB each).
    parser.add_argument("--rss-margin-mb", type=float, default=8)
    parser.add_argument("--child", choices=["generate", "stalled", "watch"], help=argparse.SUPPRESS)
    parser.add_argument("--server", help=argparse.SUPPRESS)
    parser.add_argument("--job-id", default="", help=argparse.SUPPRESS)
    args = parser.parse_args()
    if ml.import_grpc(args.python_stubs) is None:
        return ml.SKIP
    if args.child:
        return child(args)

    rng = random.Random(args.seed)
    meshd = ml.Meshd(args.meshd)
    args.server = meshd.address
    channel = ml.grpc.insecure_channel(meshd.address)
    stub = ml.service_pb2_grpc.MeshServiceStub(channel)
    problems = []
    try:
        # Warm-up: what a steady server holds (allocator arenas, gRPC buffers, a few retained
        # results), so that the RSS compared afterwards is not the first jobs' growth.
        for _ in range(3):
            call = stub.Generate(endless_generate(), timeout=RPC_TIMEOUT)
            try:
                for n, _event in enumerate(call):
                    if n == 50:
                        call.cancel()
            except ml.grpc.RpcError as e:
                assert e.code() == ml.grpc.StatusCode.CANCELLED, f"warm-up Generate: {e.code()}"
            job_id = stub.Submit(finite_job(), timeout=RPC_TIMEOUT).job_id
            list(stub.Watch(ml.service_pb2.JobRef(job_id=job_id), timeout=RPC_TIMEOUT))
        ml.wait_for("warm-up jobs to end", lambda: meshd.metric("meshd_live_jobs") == 0, 30)
        rss_start = meshd.rss_mb()
        print(f"meshd on port {meshd.port}: RSS {rss_start:.1f} MB after the warm-up", flush=True)

        expect, modes = {}, {}  # job id -> the final state it must reach; mode -> count
        t0 = time.monotonic()
        for i in range(args.iterations):
            mode = rng.choices(["generate", "stalled", "watch"], [4, 2, 4])[0]
            modes[mode] = modes.get(mode, 0) + 1
            if mode != "watch":
                expect[run_child(args, mode, "", rng)] = "JOB_STATE_CANCELLED"
            else:
                job_id = stub.Submit(finite_job(), timeout=RPC_TIMEOUT).job_id
                expect[run_child(args, "watch", job_id, rng)] = "JOB_STATE_SUCCEEDED"
        print(f"{args.iterations} clients killed mid-stream in {time.monotonic() - t0:.1f} s: "
              + ", ".join(f"{n} {mode}" for mode, n in sorted(modes.items())), flush=True)

        t1 = time.monotonic()
        try:
            ml.wait_for("meshd_live_jobs and meshd_active_streams to return to 0",
                        lambda: meshd.metric("meshd_live_jobs") == 0 and
                        meshd.metric("meshd_active_streams") == 0, SETTLE_TIMEOUT, 0.1)
            print(f"live jobs and streams back to 0 {time.monotonic() - t1:.2f} s after the "
                  f"last kill")
        except AssertionError as e:
            problems.append(f"{e}: live {meshd.metric('meshd_live_jobs'):.0f}, "
                            f"streams {meshd.metric('meshd_active_streams'):.0f}")

        jobs = {j.job_id: j for j in stub.ListJobs(ml.service_pb2.ListJobsRequest(),
                                                    timeout=RPC_TIMEOUT).jobs}
        for job_id, want in expect.items():
            got = ml.service_pb2.JobState.Name(jobs[job_id].state) if job_id in jobs else "lost"
            if got != want:
                problems.append(f"job {job_id}: {got}, expected {want}")

        # Still serving: a fresh Generate runs to done.
        events = list(stub.Generate(finite_job(), timeout=RPC_TIMEOUT))
        if not events or not events[-1].HasField("done"):
            problems.append("a Generate after the kills did not end with done")
        else:
            print(f"a Generate after the kills: {events[-1].done.nodes} nodes, done")

        # The results of the watched jobs and of that Generate are kept for --retention: they
        # are growth the server owes nobody an apology for. The rest must stay within margin.
        rss_end = meshd.rss_mb()
        retained = sum(j.done.result_bytes for j in stub.ListJobs(
            ml.service_pb2.ListJobsRequest(), timeout=RPC_TIMEOUT).jobs
            if j.job_id in expect or j.job_id == events[-1].job_id) / 2 ** 20
        growth = rss_end - rss_start - retained
        print(f"RSS: {rss_start:.1f} MB after the warm-up, {rss_end:.1f} MB after "
              f"{args.iterations} killed clients ({rss_end - rss_start:+.1f} MB, of which "
              f"{retained:.1f} MB retained results: {growth:+.1f} MB; margin "
              f"{args.rss_margin_mb:.0f} MB)")
        if growth > args.rss_margin_mb:
            ml.rss_problem(problems, f"RSS grew by {growth:.1f} MB beyond the retained results")
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
