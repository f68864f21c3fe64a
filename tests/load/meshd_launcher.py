"""What the load scripts share: a meshd child process, its /metrics, its RSS, and the stubs.

    meshd = Meshd(binary, "--cpu-workers", "2")   # --listen/--metrics on free loopback ports
    meshd.metric("meshd_live_jobs")               # a gauge or counter from /metrics
    meshd.rss_mb()                                # VmRSS of the process, MB

import_grpc(stubs_dir) returns None when this interpreter has no grpcio (the callers then exit
77, ctest's skip); after it, the module globals grpc, mesh_pb2, request_pb2, service_pb2 and
service_pb2_grpc are the real modules.
"""

import os
import re
import signal
import subprocess
import sys
import threading
import time
import urllib.request

SKIP = 77
# Under ASan or TSan (tests/CMakeLists.txt sets MESHD_SANITIZED=1) the sanitizer's allocator
# keeps freed memory in quarantine and shadow: meshd's RSS then says nothing about the server's
# own memory, so RSS bounds are reported but not enforced.
SANITIZED = os.environ.get("MESHD_SANITIZED") == "1"
grpc = mesh_pb2 = request_pb2 = service_pb2 = service_pb2_grpc = None


def import_grpc(stubs_dir):
    """Imports grpcio and the meshd.v1 stubs of <build>/python; None (and a SKIP line) when
    this interpreter lacks grpcio."""
    global grpc, mesh_pb2, request_pb2, service_pb2, service_pb2_grpc
    try:
        import grpc as grpc_module
    except ImportError as e:
        print(f"SKIP: grpcio is not available to {sys.executable} ({e}); install python3-grpcio")
        return None
    sys.path.insert(0, stubs_dir)
    from meshd.v1 import mesh_pb2 as m, request_pb2 as r, service_pb2 as s, service_pb2_grpc as g
    grpc, mesh_pb2, request_pb2, service_pb2, service_pb2_grpc = grpc_module, m, r, s, g
    return grpc


def rss_problem(problems, text):
    """Records an RSS bound that was exceeded, or only prints it under a sanitizer."""
    if SANITIZED:
        print(f"  not enforced under a sanitizer: {text}")
    else:
        problems.append(text)


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


def read_metrics(port):
    """Every unlabelled or labelled sample of meshd's /metrics: {'name{labels}': value}."""
    text = urllib.request.urlopen(f"http://127.0.0.1:{port}/metrics", timeout=10).read().decode()
    samples = {}
    for line in text.splitlines():
        m = re.match(r"^([a-zA-Z_:][\w:]*(?:\{[^}]*\})?) (\S+)$", line)
        if m:
            samples[m.group(1)] = float(m.group(2))
    return samples


def disk(h0, radius=1.0):
    """The disk of `radius` at the origin: about 1.155 pi r^2 / h0^2 nodes."""
    request = request_pb2.MeshRequest(h0=h0)
    request.geometry.circle.radius = radius
    return request


def square_with_hole(h0):
    """G2: [-1,1]^2 minus the disk r = 0.5: about 1.155 (4 - pi/4) / h0^2 nodes."""
    request = request_pb2.MeshRequest(h0=h0)
    request.geometry.difference.base.rectangle.min.x = -1
    request.geometry.difference.base.rectangle.min.y = -1
    request.geometry.difference.base.rectangle.max.x = 1
    request.geometry.difference.base.rectangle.max.y = 1
    request.geometry.difference.subtract.add().circle.radius = 0.5
    return request


class Meshd:
    """One meshd child process on free loopback ports. Its log is collected by a thread so that
    the pipe never fills; stop() sends SIGTERM and returns the exit code."""

    def __init__(self, binary, *extra):
        args = [binary, "--listen", "127.0.0.1:0", "--metrics", "127.0.0.1:0", "--backend", "cpu",
                *extra]
        self.proc = subprocess.Popen(args, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                     text=True, errors="replace")
        self.lines = []
        threading.Thread(target=lambda: self.lines.extend(l.rstrip("\n") for l in self.proc.stdout),
                         daemon=True).start()
        try:  # never leave a meshd behind: ctest would wait for it
            self.port = int(wait_for("the port in meshd's log", lambda: self._find(
                r"meshd listening on \S+ \(port (\d+)\)"), 30))
            self.metrics_port = int(wait_for("the metrics port in meshd's log", lambda: self._find(
                r"metrics at \S+ \(port (\d+)\)"), 30))
            self.address = f"127.0.0.1:{self.port}"
            # Listening comes before the workers' warm-up: wait until a call is answered.
            channel = grpc.insecure_channel(self.address)
            stub = service_pb2_grpc.MeshServiceStub(channel)
            wait_for("meshd to answer ListJobs", lambda: self._answers(stub), 60, 0.1)
            channel.close()
        except BaseException:
            self.kill()
            print("  meshd's log:\n    " + "\n    ".join(self.lines))
            raise

    def _find(self, pattern):
        if self.proc.poll() is not None:
            raise AssertionError(f"meshd exited with {self.proc.returncode} while starting")
        found = [m.group(1) for m in map(re.compile(pattern).search, list(self.lines)) if m]
        return found[0] if found else None

    @staticmethod
    def _answers(stub):
        try:
            stub.ListJobs(service_pb2.ListJobsRequest(), timeout=5)
            return True
        except grpc.RpcError:
            return False

    def metric(self, name):
        return read_metrics(self.metrics_port)[name]

    def rss_mb(self):
        """Resident set size of the meshd process (VmRSS of /proc/PID/status), in MB."""
        with open(f"/proc/{self.proc.pid}/status") as f:
            kb = int(re.search(r"^VmRSS:\s+(\d+) kB", f.read(), re.M).group(1))
        return kb / 1024

    def stop(self, timeout=60):
        """SIGTERM (drain, then exit) and the exit code; SIGKILL if it does not exit in time."""
        if self.proc.poll() is None:
            self.proc.send_signal(signal.SIGTERM)
            try:
                self.proc.wait(timeout=timeout)
            except subprocess.TimeoutExpired:
                self.kill()
                raise AssertionError(f"meshd did not exit within {timeout} s of SIGTERM")
        return self.proc.returncode

    def kill(self):
        if self.proc.poll() is None:
            self.proc.kill()
            self.proc.wait()

    def log_tail(self, n=40):
        return "\n    ".join(self.lines[-n:])
