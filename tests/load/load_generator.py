#!/usr/bin/env python3
"""Bounded load on a running meshd over loopback, then an audit: zero jobs unaccounted for.

    load_generator.py --server HOST:PORT --metrics-port N --python-stubs DIR
                      [--clients 6] [--duration 20] [--seed 1] [--json]

C client threads, each with its own channel, loop for S seconds over a seeded random mix of
disks and the square with a hole (about 300 to 20,000 nodes): Generate to the end, Generate with
a short deadline, Generate cancelled by the client mid-stream, Submit + Watch, Submit + Cancel,
invalid requests and bursts of Submits (UNAVAILABLE once the queue is full). Every call is one
record with a unique JobOptions.label, so that the server's jobs can be matched to the calls even
when the client never saw the job's id. Then it prints throughput, latency and the accounting,
and checks with the server (load_audit.py): ListJobs holds each job in the final state the
client's view implies, meshd_live_jobs and meshd_active_streams return to 0, and
meshd_jobs_total moved by exactly what the client saw. The audit assumes that nobody else
uses the server during the run and that it keeps finished jobs at least as long as the run
(--retention, --max-retained).

Exit status: 0 when every job is accounted for, 1 otherwise, 77 when grpcio is missing.
"""

import argparse
import hashlib
import json
import os
import random
import sys
import threading
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import load_audit  # noqa: E402
import meshd_launcher as ml  # noqa: E402

RPC_TIMEOUT = 120  # s: every call has a deadline, so a hang fails instead of blocking
# (size class, geometry, h0): about 1.155 * area / h0^2 nodes.
SIZES = [("small", "disk", 0.1), ("small", "hole", 0.11), ("medium", "disk", 0.04),
         ("medium", "hole", 0.03), ("large", "disk", 0.0135), ("large", "hole", 0.015)]
# What each kind of call may end as; anything else is a failure. "rejected" here means
# UNAVAILABLE (queue full), except for "invalid".
KINDS = {"generate": ({"done", "rejected"}, 30),
         "deadline": ({"deadline", "done", "rejected"}, 8),
         "stream_cancel": ({"cancelled", "rejected"}, 10),
         "submit_watch": ({"done", "rejected"}, 14),
         "submit_cancel": ({"cancel_rpc", "rejected"}, 10),
         "invalid": ({"rejected"}, 8),
         "burst": ({"done", "rejected"}, 4)}


def request_for(size, label):
    _, shape, h0 = size
    request = ml.disk(h0) if shape == "disk" else ml.square_with_hole(h0)
    area = 3.14159265 if shape == "disk" else 4 - 3.14159265 / 4
    request.options.label = label
    return request, 1.155 * area / h0 ** 2


class Client(threading.Thread):
    """One client: its own channel and random stream; appends a dict per call to `records`."""

    def __init__(self, index, args, tag, stop_at, records, lock):
        super().__init__(daemon=True)
        self.index, self.tag, self.stop_at = index, tag, stop_at
        self.rng = random.Random(args.seed * 1000 + index)
        self.records, self.lock, self.count, self.refused = records, lock, 0, False
        self.channel = ml.grpc.insecure_channel(args.server)
        self.stub = ml.service_pb2_grpc.MeshServiceStub(self.channel)

    def run(self):
        names, weights = list(KINDS), [w for _, w in KINDS.values()]
        while time.monotonic() < self.stop_at:
            getattr(self, self.rng.choices(names, weights)[0])()
            # A well-behaved client backs off when the queue is full instead of spinning.
            if self.refused:
                self.refused = False
                time.sleep(self.rng.uniform(0.05, 0.2))
        self.channel.close()

    def record(self, kind, sizes):
        size = self.rng.choice(sizes)
        self.count += 1
        label = f"{self.tag}-c{self.index}-{self.count}"
        request, estimate = request_for(size, label)
        rec = {"kind": kind, "label": label, "size": size[0], "estimate": estimate,
               "job_id": "", "outcome": None, "t0": time.time()}
        with self.lock:
            self.records.append(rec)
        return rec, request

    def failed(self, rec, error):
        """Maps a call's error to the record's outcome; `rec["stopped_at"]` is when we gave up."""
        code = error.code()
        if code == ml.grpc.StatusCode.DEADLINE_EXCEEDED:
            rec["outcome"] = "deadline"
        elif code == ml.grpc.StatusCode.CANCELLED and "stopped_at" in rec:
            rec["outcome"] = "cancelled"
        elif code in (ml.grpc.StatusCode.UNAVAILABLE, ml.grpc.StatusCode.INVALID_ARGUMENT) \
                and not rec["job_id"]:
            rec["outcome"] = "rejected"
            self.refused |= code == ml.grpc.StatusCode.UNAVAILABLE
        else:
            rec["outcome"] = "error"
        rec["code"] = code.name

    def read(self, call, rec, cancel_on=None):
        """Reads a MeshEvent stream to its end: done with the SHA-256 and node count verified, or
        the error. Cancels the call at the first event of kind `cancel_on`."""
        chunks = []
        try:
            for event in call:
                rec["job_id"] = rec["job_id"] or event.job_id
                kind = event.WhichOneof("event")
                if kind == cancel_on and "stopped_at" not in rec:
                    rec["stopped_at"] = time.time()
                    call.cancel()
                elif kind == "result_chunk":
                    chunks.append(event.result_chunk.data)
                elif kind == "done":
                    self.verify(rec, b"".join(chunks), event.done)
        except ml.grpc.RpcError as e:
            self.failed(rec, e)

    def verify(self, rec, payload, done):
        mesh = ml.mesh_pb2.MeshData.FromString(payload)
        checks = [hashlib.sha256(payload).hexdigest() == done.result_sha256,
                  len(mesh.points) == 2 * done.nodes, len(mesh.triangles) == 3 * done.triangles,
                  0.7 * rec["estimate"] < done.nodes < 1.3 * rec["estimate"]]
        rec["outcome"] = "done" if all(checks) else "bad_result"
        rec.update(sha=done.result_sha256, nodes=done.nodes, latency=time.time() - rec["t0"])

    # ---- the kinds of call --------------------------------------------------------------------
    def generate(self):
        rec, request = self.record("generate", SIZES)
        self.read(self.stub.Generate(request, timeout=RPC_TIMEOUT), rec)

    def deadline(self):
        # A large job and 0.05-0.5 s: the deadline passes while it is queued or running (or,
        # on a fast machine, the job may still make it: done is fine too).
        rec, request = self.record("deadline", SIZES[4:])
        timeout = self.rng.uniform(0.05, 0.5)
        rec["stopped_at"] = rec["t0"] + timeout
        self.read(self.stub.Generate(request, timeout=timeout), rec)

    def stream_cancel(self):
        rec, request = self.record("stream_cancel", SIZES[2:])
        self.read(self.stub.Generate(request, timeout=RPC_TIMEOUT), rec,
                  cancel_on=self.rng.choice(["queued", "started", "progress"]))

    def submit(self, rec, request):
        try:
            rec["job_id"] = self.stub.Submit(request, timeout=RPC_TIMEOUT).job_id
            return True
        except ml.grpc.RpcError as e:
            self.failed(rec, e)
            return False

    def watch(self, rec):
        ref = ml.service_pb2.JobRef(job_id=rec["job_id"])
        self.read(self.stub.Watch(ref, timeout=RPC_TIMEOUT), rec)

    def submit_watch(self):
        rec, request = self.record("submit_watch", SIZES)
        if self.submit(rec, request):
            self.watch(rec)

    def submit_cancel(self):
        rec, request = self.record("submit_cancel", SIZES[2:])
        if self.submit(rec, request):
            time.sleep(self.rng.uniform(0, 0.5))
            try:
                info = self.stub.Cancel(ml.service_pb2.JobRef(job_id=rec["job_id"]),
                                        timeout=RPC_TIMEOUT)
                rec.update(outcome="cancel_rpc", cancel_reply=info.state)
            except ml.grpc.RpcError as e:
                self.failed(rec, e)

    def invalid(self):
        rec, request = self.record("invalid", SIZES[:2])
        request.h0 = -request.h0
        if self.rng.random() < 0.5:
            self.read(self.stub.Generate(request, timeout=RPC_TIMEOUT), rec)
        else:
            self.submit(rec, request)
        if rec.get("code") != "INVALID_ARGUMENT":
            rec["outcome"] = "error"

    def burst(self):
        # Small jobs back to back, faster than the workers take them: past the queue's
        # capacity they are refused with UNAVAILABLE. The accepted ones are watched to the end.
        accepted = [rec for rec, request in (self.record("burst", SIZES[:2])
                                             for _ in range(self.rng.randint(6, 12)))
                    if self.submit(rec, request)]
        for rec in accepted:
            self.watch(rec)


def percentile(values, p):
    values = sorted(values)
    return values[min(len(values) - 1, int(p / 100 * len(values)))] if values else float("nan")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--server", required=True, help="HOST:PORT of meshd's gRPC")
    parser.add_argument("--metrics-port", type=int, required=True)
    parser.add_argument("--python-stubs", required=True, help="<build>/python (meshd.v1 stubs)")
    parser.add_argument("--clients", type=int, default=6)
    parser.add_argument("--duration", type=float, default=20, help="seconds of load")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--json", action="store_true", help="also print a one-line JSON summary")
    args = parser.parse_args()
    if ml.import_grpc(args.python_stubs) is None:
        return ml.SKIP

    tag = f"load-{args.seed}-{os.getpid()}-{int(time.time())}"
    before = ml.read_metrics(args.metrics_port)
    records, lock = [], threading.Lock()
    t0 = time.monotonic()
    clients = [Client(i, args, tag, t0 + args.duration, records, lock) for i in range(args.clients)]
    for c in clients:
        c.start()
    for c in clients:
        c.join()
    elapsed = time.monotonic() - t0

    done = sum(rec["outcome"] == "done" for rec in records)
    print(f"{args.clients} clients, {elapsed:.1f} s: {len(records)} calls "
          f"({len(records) / elapsed:.2f}/s), {done} done ({done / elapsed:.2f}/s)")
    latency = {}
    for size in ("small", "medium", "large"):
        ms = [1000 * r["latency"] for r in records
              if r["kind"] == "generate" and r["outcome"] == "done" and r["size"] == size]
        latency[size] = {"n": len(ms), "p50_ms": round(percentile(ms, 50)),
                         "p99_ms": round(percentile(ms, 99))} if ms else {"n": 0}
        if ms:
            print(f"  Generate {size:6s}: {len(ms):4d} done, p50 {latency[size]['p50_ms']:6d} ms, "
                  f"p99 {latency[size]['p99_ms']:6d} ms")

    channel = ml.grpc.insecure_channel(args.server)
    expected = {kind: outcomes for kind, (outcomes, _) in KINDS.items()}
    problems, table = load_audit.audit(args.metrics_port, ml.service_pb2_grpc.MeshServiceStub(
        channel), records, before, tag, expected)
    channel.close()
    # The accounting: each client outcome against the final state the server holds for it.
    columns = ["SUCCEEDED", "CANCELLED", "FAILED", "QUEUED", "RUNNING", "no job"]
    print(f"  {'client outcome':26s} {'calls':>6s} " + " ".join(f"{c:>9s}" for c in columns))
    for key in sorted(table):
        row = table[key]
        print(f"  {key:26s} {sum(row.values()):6d} " +
              " ".join(f"{row.get(c, 0) or '':>9}" for c in columns))
    races = [r["race_s"] for r in records if "race_s" in r]
    if races:
        print(f"  {len(races)} cancelled or deadline calls lost the race to a finishing job: "
              f"the server finished {min(races):+.3f} to {max(races):+.3f} s from the moment "
              f"the client gave up (allowed: up to +{load_audit.RACE_TOLERANCE_S:.0f} s)")
    for p in problems[:30]:
        print(f"  PROBLEM: {p}")
    if len(problems) > 30:
        print(f"  ... and {len(problems) - 30} more")
    print(f"FAIL: {len(problems)} accounting problems" if problems else
          "zero jobs unaccounted for")
    if args.json:
        print("JSON " + json.dumps({
            "clients": args.clients, "duration_s": round(elapsed, 1), "calls": len(records),
            "calls_per_s": round(len(records) / elapsed, 2), "done": done,
            "done_per_s": round(done / elapsed, 2), "latency": latency, "accounting": table,
            "problems": len(problems)}))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
