"""meshd.Client: the MeshService over a blocking gRPC channel.

    with meshd.Client("127.0.0.1:50051") as client:
        mesh = client.generate(meshd.request(meshd.circle(1) - meshd.circle(0.3), h0=0.05))
        job = client.submit(request)
        for event in client.watch(job):          # Queued, Started, Progress, Snapshot, Done
            ...
        client.cancel(job); client.jobs()

Every call has a deadline (`timeout` seconds, the client's default unless given); for a stream
it bounds the whole stream, and when a Generate call's deadline passes the server cancels the
job. Failures raise meshd.MeshdError subclasses (meshd.errors).
"""

import grpc

from meshd.connection import Connection
from meshd.errors import from_rpc_error
from meshd.events import Done, EventDecoder
from meshd.job_info import STATE_VALUES, JobInfo
from meshd.progress import close_reporter, make_reporter
from meshd.v1 import service_pb2, service_pb2_grpc

DEFAULT_ADDRESS = "127.0.0.1:50051"
DEFAULT_TIMEOUT_S = 600.0


def job_ref(job):
    """A JobRef from a job id or a JobInfo."""
    return service_pb2.JobRef(job_id=job if isinstance(job, str) else job.job_id)


def list_request(state):
    if state is None:
        return service_pb2.ListJobsRequest()
    if state not in STATE_VALUES:
        raise ValueError(f"state: one of {', '.join(STATE_VALUES)}, not {state!r}")
    return service_pb2.ListJobsRequest(state=STATE_VALUES[state])


class Client:
    """A connection to one meshd. address "HOST:PORT"; token, tls and tls_server_name as in
    meshd.connection.Connection; timeout: default deadline of every call, in seconds."""

    def __init__(self, address=DEFAULT_ADDRESS, token=None, tls=None, timeout=DEFAULT_TIMEOUT_S,
                 tls_server_name=None, options=()):
        self.connection = Connection(address, token, tls, tls_server_name, options)
        self.timeout = timeout
        self._channel = self.connection.channel(grpc)
        self._stub = service_pb2_grpc.MeshServiceStub(self._channel)

    def _call(self, timeout):
        return {"timeout": self.timeout if timeout is None else timeout,
                "metadata": self.connection.metadata}

    def _unary(self, method, message, timeout):
        try:
            return getattr(self._stub, method)(message, **self._call(timeout))
        except grpc.RpcError as e:
            raise from_rpc_error(e) from None

    def _events(self, call):
        decoder = EventDecoder()
        try:
            for proto_event in call:
                event = decoder.feed(proto_event)
                if event is not None:
                    yield event
            decoder.finish()
        except grpc.RpcError as e:
            raise from_rpc_error(e) from None
        finally:
            call.cancel()  # a reader that stops early ends the call (and a Generate's job)

    # ---- jobs and their events --------------------------------------------------------------

    def stream(self, request, timeout=None):
        """Generate: queues the request and yields its events, the last one Done(mesh). Leaving
        the loop early cancels the job."""
        return self._events(self._stub.Generate(request, **self._call(timeout)))

    def generate(self, request, progress=False, timeout=None):
        """Meshes request (a meshd.v1.MeshRequest, see meshd.request()) and returns the Mesh.
        progress: see meshd.progress (True: a bar, or a live plot in Jupyter)."""
        return consume(self.stream(request, timeout), progress, request)

    def submit(self, request, timeout=None):
        """Queues request and returns its job id at once; the job runs without this client."""
        return self._unary("Submit", request, timeout).job_id

    def watch(self, job, timeout=None):
        """Yields a job's events from its start (a finished one: Done at once)."""
        return self._events(self._stub.Watch(job_ref(job), **self._call(timeout)))

    def result(self, job, progress=False, timeout=None):
        """Waits for a submitted job and returns its Mesh."""
        return consume(self.watch(job, timeout), progress)

    def cancel(self, job, timeout=None):
        """Cancels a queued or running job; returns its JobInfo."""
        return JobInfo.from_proto(self._unary("Cancel", job_ref(job), timeout))

    def job(self, job, timeout=None):
        """The JobInfo of one job."""
        return JobInfo.from_proto(self._unary("GetJob", job_ref(job), timeout))

    def jobs(self, state=None, timeout=None):
        """The server's jobs in submission order, optionally only those in state ("queued",
        "running", "succeeded", "failed", "cancelled")."""
        reply = self._unary("ListJobs", list_request(state), timeout)
        return [JobInfo.from_proto(info) for info in reply.jobs]

    # ---- lifetime -----------------------------------------------------------------------------

    def close(self):
        self._channel.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()


def consume(events, progress, request=None):
    """Reads events to the end, showing them through the progress reporter; returns the mesh."""
    reporter = make_reporter(progress, request)
    mesh = None
    try:
        for event in events:
            if reporter is not None:
                reporter(event)
            if isinstance(event, Done):
                mesh = event.mesh
    finally:
        close_reporter(reporter)
    return mesh
