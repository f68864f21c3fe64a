#!/usr/bin/env python3
"""Each kind of failure through the installed meshd package, against a real meshd: a bad field
(InvalidArgument with its path), an unknown job (NotFound), no server (Unavailable), a missing or
wrong token (Unauthenticated), TLS with and without a client certificate, a cancelled job
(Cancelled) and a passed deadline (DeadlineExceeded).

    failure_checks.py --meshd BIN --tmp DIR   (run with the interpreter the package is installed in)
"""

import os
import shutil
import socket
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from check_runner import Skip  # noqa: E402
from client_helpers import (BIG, HERE, SHORT_DEADLINE_S, TIMEOUT_S, MeshdChild,  # noqa: E402
                            check_ring, expect, main, ring, wait_for_state)

import meshd  # noqa: E402


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


def test_tls(ctx):
    """TLS with a client certificate, as meshctl's --tls-ca, --tls-cert and --tls-key."""
    if not shutil.which("openssl"):
        raise Skip("no openssl to make test certificates")
    certs = os.path.join(ctx.tmp, "certs")
    subprocess.run(["sh", os.path.join(HERE, os.pardir, "server", "make_test_certs.sh"), certs],
                   check=True, capture_output=True, timeout=TIMEOUT_S)
    pem = lambda name: os.path.join(certs, name)  # noqa: E731
    with MeshdChild(ctx.binary, "--tls-cert", pem("server.pem"), "--tls-key", pem("server.key"),
                    "--tls-client-ca", pem("ca.pem")) as server:
        tls = meshd.tls_credentials(ca=pem("ca.pem"), cert=pem("client.pem"),
                                    key=pem("client.key"))
        with meshd.Client(server.address, tls=tls, timeout=TIMEOUT_S) as client:
            check_ring(client.generate(ring()))
        for refused in (meshd.tls_credentials(ca=pem("ca.pem")), None):  # no certificate; plain
            with meshd.Client(server.address, tls=refused, timeout=TIMEOUT_S) as client:
                expect(meshd.Unavailable, lambda: client.jobs())


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


if __name__ == "__main__":
    sys.exit(main([test_invalid_argument, test_not_found, test_unavailable, test_unauthenticated,
                   test_tls, test_cancelled, test_deadline_exceeded]))
