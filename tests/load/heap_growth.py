#!/usr/bin/env python3
"""Server heap under repeated load: valgrind massif measures meshd's heap after each round.

    heap_growth.py --meshd BIN --python-stubs DIR [--rounds 6] [--calls 24] [--margin-kb 64]

Starts BIN under `valgrind --tool=massif` and drives it with identical rounds of calls on
loopback: Generate to the end, Generate abandoned by the client mid-stream, Submit + Cancel,
Submit + Watch, and invalid requests. After each round, once meshd_live_jobs and
meshd_active_streams are back to 0, it asks massif for a snapshot through vgdb and reads the
heap in use (payload plus allocator overhead). The first round warms the caches and fills the
retained results (capped with --max-retained), so the baseline is the heap after round 2; every
later round must end within --margin-kb of it. Finally SIGTERM must end meshd with 0.

Exit status: 0 when the heap does not grow, 1 otherwise, 77 when grpcio or valgrind is missing.
"""

import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile
import threading

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import meshd_launcher as ml  # noqa: E402

RPC_TIMEOUT = 300  # s: meshd runs some 20-50 times slower under valgrind
# The results meshd keeps stop growing after the first round.
MESHD_FLAGS = ["--cpu-workers", "2", "--cpu-threads", "1", "--queue-capacity", "64",
               "--retention", "3600", "--max-retained", "8"]


def one_call(stub, kind, index):
    """One call of the round; raises on any outcome other than the one `kind` must have."""
    request = ml.disk(0.12 if index % 2 else 0.15)
    request.options.label = f"heap-{kind}-{index}"
    if kind == "generate":
        events = list(stub.Generate(request, timeout=RPC_TIMEOUT))
        assert events[-1].HasField("done"), f"{kind}: the stream ended without done"
    elif kind == "abandon":
        request.options.snapshot_every = 1
        call = stub.Generate(request, timeout=RPC_TIMEOUT)
        next(call)  # queued or started: the job exists, then the client goes away
        call.cancel()
    elif kind == "submit_cancel":
        job = stub.Submit(request, timeout=RPC_TIMEOUT)
        stub.Cancel(job, timeout=RPC_TIMEOUT)
    elif kind == "submit_watch":
        job = stub.Submit(request, timeout=RPC_TIMEOUT)
        events = list(stub.Watch(job, timeout=RPC_TIMEOUT))
        assert events[-1].HasField("done"), f"{kind}: the stream ended without done"
    elif kind == "invalid":
        request.h0 = -1
        try:
            next(stub.Generate(request, timeout=RPC_TIMEOUT))
            raise AssertionError("a negative h0 was accepted")
        except ml.grpc.RpcError as e:
            assert e.code() == ml.grpc.StatusCode.INVALID_ARGUMENT, e


def run_round(address, calls):
    """`calls` calls on four client threads, each with its own channel; returns the errors."""
    kinds = ["generate", "abandon", "submit_cancel", "submit_watch", "invalid"]
    errors, lock = [], threading.Lock()

    def client(first):
        channel = ml.grpc.insecure_channel(address)
        stub = ml.service_pb2_grpc.MeshServiceStub(channel)
        for i in range(first, calls, 4):
            try:
                one_call(stub, kinds[i % len(kinds)], i)
            except Exception as e:  # noqa: BLE001 - every failure is reported
                with lock:
                    errors.append(f"call {i} ({kinds[i % len(kinds)]}): {e!r}")
        channel.close()

    threads = [threading.Thread(target=client, args=(t,)) for t in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    return errors


def heap_bytes(pid, path):
    """Heap in use now (massif's mem_heap_B + mem_heap_extra_B), from a vgdb snapshot."""
    subprocess.run(["vgdb", f"--pid={pid}", "snapshot", path], stdout=subprocess.DEVNULL,
                   stderr=subprocess.DEVNULL, timeout=120)
    ml.wait_for("massif's snapshot", lambda: os.path.exists(path), 120)
    text = open(path).read()
    heap = int(re.search(r"^mem_heap_B=(\d+)", text, re.M).group(1))
    extra = int(re.search(r"^mem_heap_extra_B=(\d+)", text, re.M).group(1))
    return heap + extra


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--meshd", required=True)
    parser.add_argument("--python-stubs", required=True)
    parser.add_argument("--rounds", type=int, default=6)
    parser.add_argument("--calls", type=int, default=24, help="calls per round")
    parser.add_argument("--margin-kb", type=int, default=64,
                        help="allowed heap above the baseline at the end of a round")
    args = parser.parse_args()
    if ml.import_grpc(args.python_stubs) is None:
        return ml.SKIP
    if not (shutil.which("valgrind") and shutil.which("vgdb")):
        print("SKIP: valgrind (with vgdb) is not installed")
        return ml.SKIP

    work = tempfile.mkdtemp(prefix="meshd-heap-")
    # massif runs meshd; ml.Meshd passes its flags after the binary, so valgrind is the binary.
    wrapper = os.path.join(work, "meshd-under-massif")
    with open(wrapper, "w") as f:
        f.write(f"#!/bin/sh\nexec valgrind --tool=massif --vgdb=yes --massif-out-file="
                f"{work}/massif.out {os.path.abspath(args.meshd)} \"$@\"\n")
    os.chmod(wrapper, 0o755)
    meshd = ml.Meshd(wrapper, *MESHD_FLAGS)
    try:
        heaps, failures = [], []
        for r in range(1, args.rounds + 1):
            errors = run_round(meshd.address, args.calls)
            failures += [f"round {r}: {e}" for e in errors]
            ml.wait_for("no live jobs and no open streams", lambda: meshd.metric(
                "meshd_live_jobs") == 0 and meshd.metric("meshd_active_streams") == 0, 120, 0.2)
            heaps.append(heap_bytes(meshd.proc.pid, os.path.join(work, f"round{r}.massif")))
            print(f"round {r}: {args.calls} calls, {len(errors)} errors, "
                  f"heap {heaps[-1] / 1024:.0f} KiB", flush=True)
        baseline = heaps[min(1, len(heaps) - 1)]
        for r, heap in enumerate(heaps[2:], start=3):
            if heap > baseline + 1024 * args.margin_kb:
                failures.append(f"round {r}: heap {heap / 1024:.0f} KiB, more than "
                                f"{args.margin_kb} KiB above round 2's {baseline / 1024:.0f} KiB")
        growth = (heaps[-1] - baseline) / 1024
        print(f"heap after round 2: {baseline / 1024:.0f} KiB; after round {len(heaps)}: "
              f"{heaps[-1] / 1024:.0f} KiB ({growth:+.0f} KiB; margin {args.margin_kb} KiB)")
        code = meshd.stop(timeout=300)
        if code != 0:
            failures.append(f"meshd exited {code} after SIGTERM")
        for f in failures[:20]:
            print(f"  PROBLEM: {f}")
        print(f"FAIL: {len(failures)} problems" if failures else "PASS: no heap growth")
        return 1 if failures else 0
    finally:
        meshd.kill()
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
