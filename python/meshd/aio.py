"""meshd.aio.Client: the same calls as meshd.Client, over grpc.aio, for asyncio code.

    async with meshd.aio.Client("127.0.0.1:50051") as client:
        mesh = await client.generate(request)
        job = await client.submit(request)
        async for event in client.watch(job):
            ...

Create it inside the event loop that uses it (grpc.aio binds a channel to its loop). To leave a
stream early, close it (`await events.aclose()`, or `async with contextlib.aclosing(...)`): an
async generator left open keeps its call, and a Generate call its job, until it is collected.
"""

import grpc
import grpc.aio

from meshd.client import DEFAULT_ADDRESS, DEFAULT_TIMEOUT_S, job_ref, list_request
from meshd.connection import Connection
from meshd.errors import from_rpc_error
from meshd.events import Done, EventDecoder
from meshd.job_info import JobInfo
from meshd.progress import close_reporter, make_reporter
from meshd.v1 import service_pb2_grpc


class Client:
    """See meshd.Client; every method is a coroutine, stream() and watch() async iterators."""

    def __init__(self, address=DEFAULT_ADDRESS, token=None, tls=None, timeout=DEFAULT_TIMEOUT_S,
                 tls_server_name=None, options=()):
        self.connection = Connection(address, token, tls, tls_server_name, options)
        self.timeout = timeout
        self._channel = self.connection.channel(grpc.aio)
        self._stub = service_pb2_grpc.MeshServiceStub(self._channel)

    def _call(self, timeout):
        return {"timeout": self.timeout if timeout is None else timeout,
                "metadata": self.connection.metadata}

    async def _unary(self, method, message, timeout):
        try:
            return await getattr(self._stub, method)(message, **self._call(timeout))
        except grpc.RpcError as e:
            raise from_rpc_error(e) from None

    async def _events(self, call):
        decoder = EventDecoder()
        try:
            async for proto_event in call:
                event = decoder.feed(proto_event)
                if event is not None:
                    yield event
            decoder.finish()
        except grpc.RpcError as e:
            raise from_rpc_error(e) from None
        finally:
            call.cancel()  # a reader that stops early ends the call (and a Generate's job)

    def stream(self, request, timeout=None):
        return self._events(self._stub.Generate(request, **self._call(timeout)))

    async def generate(self, request, progress=False, timeout=None):
        return await consume(self.stream(request, timeout), progress, request)

    async def submit(self, request, timeout=None):
        return (await self._unary("Submit", request, timeout)).job_id

    def watch(self, job, timeout=None):
        return self._events(self._stub.Watch(job_ref(job), **self._call(timeout)))

    async def result(self, job, progress=False, timeout=None):
        return await consume(self.watch(job, timeout), progress)

    async def cancel(self, job, timeout=None):
        return JobInfo.from_proto(await self._unary("Cancel", job_ref(job), timeout))

    async def job(self, job, timeout=None):
        return JobInfo.from_proto(await self._unary("GetJob", job_ref(job), timeout))

    async def jobs(self, state=None, timeout=None):
        reply = await self._unary("ListJobs", list_request(state), timeout)
        return [JobInfo.from_proto(info) for info in reply.jobs]

    async def close(self):
        await self._channel.close()

    async def __aenter__(self):
        return self

    async def __aexit__(self, *exc):
        await self.close()


async def consume(events, progress, request=None):
    reporter = make_reporter(progress, request)
    mesh = None
    try:
        async for event in events:
            if reporter is not None:
                reporter(event)
            if isinstance(event, Done):
                mesh = event.mesh
    finally:
        close_reporter(reporter)
    return mesh
