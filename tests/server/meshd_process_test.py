#!/usr/bin/env python3
"""The real meshd process, driven by grpcio: a client that nobody on the team wrote.

    meshd_process_test.py --meshd BIN --python-stubs DIR

Starts `BIN --listen 127.0.0.1:0 --metrics 127.0.0.1:0 --backend cpu`, reads both ports from its
log and runs the sub-tests below against it (Generate, Submit + Watch, bad requests, metrics),
then two more meshd processes for SIGTERM: one whose running job outlives --drain-timeout (it is
cancelled and the process still exits 0) and one whose job finishes within it (it completes).

Exit status: 0 when all pass, 1 on a failure, 77 (ctest's skip) when grpcio is missing.
"""

import argparse
import hashlib
import math
import re
import signal
import subprocess
import sys
import threading
import time
import urllib.request

SKIP = 77
RPC_TIMEOUT = 120  # seconds; every call has a deadline, so a hang fails instead of blocking
HEALTH_CHECK = "/grpc.health.v1.Health/Check"
SERVING, NOT_SERVING = 1, 2


def wait_for(what, predicate, timeout, interval=0.05):
    """Polls predicate() until it returns a true value; fails naming `what` after `timeout`."""
    deadline = time.monotonic() + timeout
    while True:
        value = predicate()
        if value:
            return value
        if time.monotonic() > deadline:
            raise AssertionError(f"timed out after {timeout} s waiting for {what}")
        time.sleep(interval)


class Meshd:
    """One meshd child process. Its log is collected by a thread so that the pipe never fills."""

    def __init__(self, binary, *extra):
        args = [binary, "--listen", "127.0.0.1:0", "--metrics", "127.0.0.1:0", "--backend", "cpu",
                *extra]
        self.proc = subprocess.Popen(args, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                     text=True, errors="replace")
        self.lines, self.channel = [], None
        threading.Thread(target=lambda: self.lines.extend(l.rstrip("\n") for l in self.proc.stdout),
                         daemon=True).start()
        try:  # never leave a meshd behind: ctest would wait for it
            self.port = int(wait_for("the port in meshd's log", lambda: self._find(
                r"meshd listening on \S+ \(port (\d+)\)"), 30))
            self.metrics_port = int(wait_for("the metrics port in meshd's log", lambda: self._find(
                r"metrics at \S+ \(port (\d+)\)"), 30))
            self.channel = grpc.insecure_channel(f"127.0.0.1:{self.port}")
            self.stub = service_pb2_grpc.MeshServiceStub(self.channel)
            self._health = self.channel.unary_unary(HEALTH_CHECK, request_serializer=lambda x: x,
                                                    response_deserializer=lambda x: x)
            # Listening comes before warm-up; SERVING only after it.
            wait_for("health SERVING", lambda: self.health() == SERVING, 60)
        except BaseException:
            self.__exit__(*sys.exc_info())
            raise

    def _find(self, pattern):
        if self.proc.poll() is not None:
            raise AssertionError(f"meshd exited with {self.proc.returncode} while starting")
        found = [m.group(1) for m in map(re.compile(pattern).search, list(self.lines)) if m]
        return found[0] if found else None

    def health(self):
        """SERVING or NOT_SERVING from a raw Health/Check (field 1, a varint); None when the
        server cannot be reached (refused, or shutting down)."""
        try:
            body = self._health(b"", timeout=5)
        except grpc.RpcError as e:
            if e.code() == grpc.StatusCode.UNAVAILABLE:
                return None
            raise
        return body[1] if len(body) == 2 and body[0] == 0x08 else 0

    def not_serving(self):
        """None while SERVING; else what a probe sees: "NOT_SERVING", "refused" or another."""
        health = self.health()
        names = {SERVING: None, NOT_SERVING: "NOT_SERVING", None: "refused"}
        return names.get(health, f"status {health}")

    def metric(self, name, labels):
        url = f"http://127.0.0.1:{self.metrics_port}/metrics"
        text = urllib.request.urlopen(url, timeout=10).read().decode()
        m = re.search(rf"^{name}\{{{re.escape(labels)}\}} (\S+)$", text, re.M)
        assert m, f"no {name}{{{labels}}} in /metrics"
        return float(m.group(1))

    def stop(self):
        if self.proc.poll() is None:
            self.proc.kill()
            self.proc.wait()
        if self.channel:
            self.channel.close()

    def __enter__(self):
        return self

    def __exit__(self, kind, value, traceback):
        self.stop()
        if kind is not None:  # a failed sub-test: its server's side of the story
            print("  meshd's log:\n    " + "\n    ".join(self.lines))


def disk(h0, **params):
    request = request_pb2.MeshRequest(h0=h0)
    request.geometry.circle.radius = 1.0
    request.options.backend = request_pb2.JobOptions.BACKEND_CPU
    for name, value in params.items():
        setattr(request.params, name, value)
    return request


def read_events(stream, events=None):
    """Reads a MeshEvent stream to its end into `events`: (events, final status code)."""
    events = [] if events is None else events
    try:
        events.extend(stream)
    except grpc.RpcError as e:
        return events, e.code()
    return events, stream.code()


def check_mesh_stream(events, code):
    """The stream of a disk of radius 1: order, checksum and the mesh itself. Returns done."""
    assert code == grpc.StatusCode.OK, f"stream ended with {code}"
    kinds = " ".join(e.WhichOneof("event") for e in events)
    assert re.fullmatch(r"(queued )+started ((progress|snapshot) )*(result_chunk )+done", kinds), \
        f"event order: {kinds}"
    assert len({e.job_id for e in events}) == 1 and events[0].job_id, "job ids differ"
    chunks = [e.result_chunk for e in events if e.HasField("result_chunk")]
    payload = b""
    for i, c in enumerate(chunks):
        assert (c.index, c.count, c.offset) == (i, len(chunks), len(payload)), f"chunk {i}: {c}"
        payload += c.data
    done = events[-1].done
    assert chunks[0].total_bytes == len(payload) == done.result_bytes, "result length"
    assert hashlib.sha256(payload).hexdigest() == done.result_sha256, "result SHA-256"

    mesh = mesh_pb2.MeshData.FromString(payload)
    n, pts, tri = done.nodes, mesh.points, mesh.triangles
    assert len(pts) == 2 * n and len(tri) == 3 * done.triangles, "array sizes vs done"
    assert all(0 <= i < n for i in tri), "triangle index out of range"
    area = 0.0
    for t in range(0, len(tri), 3):
        a, b, c = tri[t], tri[t + 1], tri[t + 2]
        cross = ((pts[2 * b] - pts[2 * a]) * (pts[2 * c + 1] - pts[2 * a + 1]) -
                 (pts[2 * b + 1] - pts[2 * a + 1]) * (pts[2 * c] - pts[2 * a]))
        assert cross > 0, f"triangle {t // 3} is not counter-clockwise (2A = {cross})"
        area += cross / 2
    # Boundary nodes lie on the circle, so the mesh is an inscribed polygon: a little under pi.
    assert 0.98 * math.pi < area <= math.pi * (1 + 1e-6), f"area {area}, pi {math.pi}"
    assert done.quality.q_min >= 0.6, f"q_min {done.quality.q_min}"
    return done


# ---- sub-tests on one meshd ----------------------------------------------------------------------

def test_generate(meshd, state):
    events, code = read_events(meshd.stub.Generate(disk(0.05), timeout=RPC_TIMEOUT))
    done = check_mesh_stream(events, code)
    state["succeeded"] += 1
    print(f"  {done.nodes} nodes, {done.triangles} triangles, q_min {done.quality.q_min:.3f}")


def test_submit_watch(meshd, state):
    job_id = meshd.stub.Submit(disk(0.05), timeout=RPC_TIMEOUT).job_id
    ref = service_pb2.JobRef(job_id=job_id)
    events, code = read_events(meshd.stub.Watch(ref, timeout=RPC_TIMEOUT))
    check_mesh_stream(events, code)
    assert events[0].job_id == job_id, "Watch streamed another job"
    state["succeeded"] += 1
    info = meshd.stub.GetJob(ref, timeout=RPC_TIMEOUT)
    assert info.state == service_pb2.JOB_STATE_SUCCEEDED, f"GetJob state {info.state}"
    jobs = meshd.stub.ListJobs(service_pb2.ListJobsRequest(), timeout=RPC_TIMEOUT).jobs
    listed = {j.job_id: j.state for j in jobs}
    assert listed.get(job_id) == service_pb2.JOB_STATE_SUCCEEDED, f"ListJobs: {listed}"


def test_bad_requests(meshd, state):
    no_radius = disk(0.05)
    no_radius.geometry.circle.radius = 0
    cases = [("Generate", disk(-1), "h0"),
             ("Submit", disk(-1), "h0"),
             ("Generate", no_radius, "geometry.circle.radius"),
             ("Submit", no_radius, "geometry.circle.radius")]
    for rpc, request, field in cases:
        try:
            reply = getattr(meshd.stub, rpc)(request, timeout=RPC_TIMEOUT)
            if rpc == "Generate":
                list(reply)
            raise AssertionError(f"{rpc} accepted a bad {field}")
        except grpc.RpcError as e:
            assert e.code() == grpc.StatusCode.INVALID_ARGUMENT, f"{rpc}: {e.code()}"
            assert re.search(rf"(^|\W){re.escape(field)}\W", e.details()), \
                f"{rpc}: details do not name {field}: {e.details()!r}"
        state["rejected"] += 1
    # Still serving: healthy, and a good request right after meshes.
    assert meshd.health() == SERVING, "health after bad requests"
    check_mesh_stream(*read_events(meshd.stub.Generate(disk(0.2), timeout=RPC_TIMEOUT)))
    state["succeeded"] += 1


def raw_call(meshd, method, payload):
    """Calls `method` with `payload` as its request's bytes: (status code, details)."""
    path = f"/meshd.v1.MeshService/{method}"
    streams = method in ("Generate", "Watch")
    call = (meshd.channel.unary_stream if streams else meshd.channel.unary_unary)(
        path, request_serializer=lambda x: x, response_deserializer=lambda x: x)
    try:
        reply = call(payload, timeout=RPC_TIMEOUT)
        if streams:
            list(reply)
        return grpc.StatusCode.OK, ""
    except grpc.RpcError as e:
        return e.code(), e.details()


def nested_request(levels):
    """A disk under `levels` translations, each two protobuf messages deep."""
    request = disk(0.2)
    for _ in range(levels):
        outer = request_pb2.MeshRequest()
        outer.CopyFrom(request)
        outer.geometry.ClearField("circle")
        outer.geometry.translate.shape.CopyFrom(request.geometry)
        request = outer
    return request.SerializeToString()


def test_unparseable_requests(meshd, state):
    """Bytes protobuf cannot parse get INVALID_ARGUMENT saying why, on every method (gRPC's own
    handlers answer UNIMPLEMENTED with no message)."""
    garbage = b"\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\x01\x0a\x05ab"
    for method, message in (("Generate", "MeshRequest"), ("Submit", "MeshRequest"),
                            ("Watch", "JobRef"), ("Cancel", "JobRef"), ("GetJob", "JobRef"),
                            ("ListJobs", "ListJobsRequest")):
        code, details = raw_call(meshd, method, garbage)
        assert code == grpc.StatusCode.INVALID_ARGUMENT, f"{method}: {code} {details!r}"
        assert f"could not be parsed as meshd.v1.{message}" in details, f"{method}: {details!r}"
        assert "wire format" in details, f"{method}: the reason is missing: {details!r}"
        print(f"  {method}: {details}")
    state["rejected"] += 2
    # Nested past protobuf's recursion limit (100): said so. Below it, our own limit speaks.
    code, details = raw_call(meshd, "Submit", nested_request(60))
    assert code == grpc.StatusCode.INVALID_ARGUMENT, f"deep tree: {code} {details!r}"
    assert "more than 100 levels deep" in details, f"deep tree: {details!r}"
    print(f"  60 nested transforms: {details}")
    code, details = raw_call(meshd, "Submit", nested_request(40))
    assert code == grpc.StatusCode.INVALID_ARGUMENT and "geometry" in details, details
    state["rejected"] += 2
    # An echoed input stays short: a 100,000-character job id is not sent back whole.
    ref = service_pb2.JobRef(job_id="x" * 100_000)
    for method in ("GetJob", "Cancel", "Watch"):
        code, details = raw_call(meshd, method, ref.SerializeToString())
        assert code == grpc.StatusCode.NOT_FOUND, f"{method}: {code} {details[:200]!r}"
        assert len(details) < 300, f"{method}: a {len(details)}-character message"
    print(f"  a 100,000-character job id: {details}")
    assert meshd.health() == SERVING, "health after unparseable requests"


def test_metrics(meshd, state):
    def succeeded():
        return meshd.metric("meshd_jobs_total", 'outcome="succeeded"')
    # Jobs are counted as they finish, which may be a moment after their done event went out.
    wait_for("the count of succeeded jobs", lambda: succeeded() >= state["succeeded"], 10)
    assert succeeded() == state["succeeded"], f"succeeded {succeeded()}, expected {state}"
    rejected = meshd.metric("meshd_jobs_total", 'outcome="rejected"')
    assert rejected >= state["rejected"], f"rejected {rejected}, expected >= {state}"


# ---- SIGTERM, each on its own meshd --------------------------------------------------------------

def test_reflection(meshd, state):
    """Server reflection (what grpcurl uses) lists the services. A raw call: the request is
    list_services = "" (field 7, an empty string); the answer carries the names as strings."""
    info = meshd.channel.stream_stream(
        "/grpc.reflection.v1alpha.ServerReflection/ServerReflectionInfo",
        request_serializer=lambda x: x, response_deserializer=lambda x: x)
    answers = list(info(iter([b"\x3a\x00"]), timeout=10))
    assert len(answers) == 1, f"{len(answers)} answers"
    for name in (b"meshd.v1.MeshService", b"grpc.health.v1.Health"):
        assert name in answers[0], f"{name.decode()} not listed: {answers[0]!r}"


def watch_in_background(meshd, job_id):
    """Opens Watch on `job_id` and returns once the job has started: (events, result, thread).
    `events` keeps filling; `result` gets the final "code" and the "end" time (monotonic)."""
    events, result = [], {}
    stream = meshd.stub.Watch(service_pb2.JobRef(job_id=job_id), timeout=RPC_TIMEOUT)

    def read():
        result["code"] = read_events(stream, events)[1]
        result["end"] = time.monotonic()
    thread = threading.Thread(target=read, daemon=True)
    thread.start()
    wait_for("the job to start", lambda: any(e.HasField("started") for e in events), 60)
    return events, result, thread


def test_sigterm_cancels_after_grace(binary):
    with Meshd(binary, "--drain-timeout", "1") as meshd:
        # Never done within the test: dptol far below what the nodes can reach, 36k nodes.
        forever = disk(0.01, dptol=1e-9, max_iterations=100000)
        job_id = meshd.stub.Submit(forever, timeout=RPC_TIMEOUT).job_id
        events, result, thread = watch_in_background(meshd, job_id)
        t0 = time.monotonic()
        meshd.proc.send_signal(signal.SIGTERM)
        # Load balancers must stop sending work at once, not after the drain.
        health = wait_for("health NOT_SERVING or refused", meshd.not_serving, 1.0, 0.02)
        print(f"  {health} {time.monotonic() - t0:.2f} s after SIGTERM")
        code = meshd.proc.wait(timeout=10)
        print(f"  exited {code} {time.monotonic() - t0:.2f} s after SIGTERM")
        assert code == 0, f"exit code {code}"
        thread.join(timeout=10)
        assert result.get("code") == grpc.StatusCode.CANCELLED, f"Watch ended {result}"
        assert not any(e.HasField("done") for e in events), "the job was not cancelled"
        # Cancelled only once the grace had passed, not at the signal.
        grace = result["end"] - t0
        print(f"  Watch ended CANCELLED {grace:.2f} s after SIGTERM")
        assert grace >= 0.9, f"cancelled {grace:.2f} s after SIGTERM, before the 1 s grace"


def test_sigterm_lets_job_finish(binary):
    with Meshd(binary, "--drain-timeout", "120") as meshd:
        # About a second of work in a Release build (about 9,000 nodes for a fixed 3,000
        # iterations), so that SIGTERM lands while it runs; under ASan on two busy cores it took
        # 30 s for twice the iterations, so the grace is four times that.
        job = disk(0.02, dptol=1e-9, max_iterations=3000)
        job_id = meshd.stub.Submit(job, timeout=RPC_TIMEOUT).job_id
        events, result, thread = watch_in_background(meshd, job_id)
        meshd.proc.send_signal(signal.SIGTERM)
        health = wait_for("health NOT_SERVING or refused", meshd.not_serving, 1.0, 0.02)
        # New work is refused during the drain.
        try:
            meshd.stub.Submit(disk(0.2), timeout=RPC_TIMEOUT)
            raise AssertionError("Submit accepted during the drain")
        except grpc.RpcError as e:
            assert e.code() == grpc.StatusCode.UNAVAILABLE, f"Submit during drain: {e.code()}"
            print(f"  Submit during the drain: UNAVAILABLE {e.details()!r}")
        running = not any(e.HasField("done") for e in events)
        assert running, "the job finished before the drain began: make it larger"
        # The server still listens while its job runs, so health must say so itself.
        assert health == "NOT_SERVING", f"health during the drain: {health}"
        code = meshd.proc.wait(timeout=150)
        assert code == 0, f"exit code {code}"
        thread.join(timeout=10)
        done = check_mesh_stream(events, result.get("code"))
        print(f"  job was running at SIGTERM and finished: {done.nodes} nodes, "
              f"{done.stats.iterations} iterations in {done.stats.t_mesh:.2f} s; exit {code}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--meshd", required=True, help="the meshd executable")
    parser.add_argument("--python-stubs", required=True, help="<build>/python (meshd.v1 stubs)")
    args = parser.parse_args()
    global grpc, service_pb2, service_pb2_grpc, request_pb2, mesh_pb2
    try:
        import grpc
    except ImportError as e:
        print(f"SKIP: grpcio is not available to {sys.executable} ({e}); install python3-grpcio")
        return SKIP
    sys.path.insert(0, args.python_stubs)
    from meshd.v1 import mesh_pb2, request_pb2, service_pb2, service_pb2_grpc

    failed = []

    def run(name, test, *test_args):
        print(f"=== {name}", flush=True)
        t = time.monotonic()
        try:
            test(*test_args)
            print(f"--- PASS {name} ({time.monotonic() - t:.1f} s)", flush=True)
        except Exception as e:  # noqa: BLE001 - every failure is reported, then the next runs
            failed.append(name)
            print(f"--- FAIL {name}: {type(e).__name__}: {e}", flush=True)

    def one_server():
        with Meshd(args.meshd) as meshd:
            print(f"  meshd on port {meshd.port}, metrics on port {meshd.metrics_port}: SERVING")
            state = {"succeeded": 0, "rejected": 0}
            run("generate_disk", test_generate, meshd, state)
            run("submit_watch_getjob_listjobs", test_submit_watch, meshd, state)
            run("bad_requests_name_the_field", test_bad_requests, meshd, state)
            run("unparseable_requests_say_why", test_unparseable_requests, meshd, state)
            run("metrics_count_jobs", test_metrics, meshd, state)
            run("reflection_lists_services", test_reflection, meshd, state)
            if failed:
                raise AssertionError(f"{len(failed)} sub-tests failed")  # prints the log

    run("start_and_health_serving", one_server)
    run("sigterm_cancels_after_grace", test_sigterm_cancels_after_grace, args.meshd)
    run("sigterm_lets_job_finish", test_sigterm_lets_job_finish, args.meshd)
    print(f"FAILED: {', '.join(failed)}" if failed else "all passed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
