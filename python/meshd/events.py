"""A job's events as typed Python objects, decoded from the meshd.v1.MeshEvent stream.

A stream reads, in order: Queued (again when its position changes, at most every 0.1 s), Started,
Progress and Snapshot interleaved, then Done, which carries the assembled Mesh. The result chunks
in between are joined and checked (order, size, SHA-256) by EventDecoder and never shown. The sync
and the async clients share the decoder; it does no I/O.
"""

import hashlib
from dataclasses import dataclass
from typing import Union

import numpy as np

from meshd.errors import BadResult
from meshd.mesh import Mesh, TetMesh, mesh_from_proto
from meshd.request import BACKEND_NAMES
from meshd.v1 import mesh_pb2


@dataclass(frozen=True)
class Queued:
    job_id: str
    position: int  # jobs ahead of this one (0: next)


@dataclass(frozen=True)
class Started:
    job_id: str
    backend: str  # "gpu" or "cpu"
    device: str
    queue_wait_s: float


@dataclass(frozen=True)
class Progress:
    job_id: str
    iteration: int
    max_move: float  # largest interior node move of the last step, relative to h0
    retriangulations: int
    flips: int
    nodes: int
    elapsed_s: float


@dataclass(frozen=True, eq=False)
class Snapshot:
    """The nodes at one iteration. triangles is the latest triangulation the stream carried
    (None before the first); topology_changed says whether this snapshot brought it. A volume's
    snapshot has points #N by 3 and tetrahedra in place of triangles (which is then None)."""
    job_id: str
    iteration: int
    points: np.ndarray  # #N by 2 (#N by 3 for a volume)
    triangles: np.ndarray  # #M by 3, or None
    topology_changed: bool
    tetrahedra: np.ndarray = None  # a volume's: #M by 4, or None


@dataclass(frozen=True, eq=False)
class Done:
    job_id: str
    mesh: Union[Mesh, TetMesh]  # a TetMesh for a volume


class EventDecoder:
    """Turns one stream's MeshEvents into the events above: feed() each in order, then finish()
    once the stream ended with OK."""

    def __init__(self):
        self.job_id = ""
        self._chunks = []
        self._received = 0
        self._triangles = None
        self._tetrahedra = None
        self.done = None

    def feed(self, event):
        """The typed event for a meshd.v1.MeshEvent, or None for a result chunk."""
        self.job_id = event.job_id or self.job_id
        kind = event.WhichOneof("event")
        if kind == "queued":
            return Queued(event.job_id, event.queued.position)
        if kind == "started":
            s = event.started
            return Started(event.job_id, BACKEND_NAMES.get(s.backend, ""), s.device,
                           s.queue_wait_s)
        if kind == "progress":
            p = event.progress
            return Progress(event.job_id, p.iteration, p.max_move, p.retriangulations, p.flips,
                            p.nodes, p.elapsed_s)
        if kind == "snapshot":
            s = event.snapshot
            if s.dimension == 3:
                if s.has_tetrahedra:
                    self._tetrahedra = np.array(s.tetrahedra, dtype=np.int32).reshape(-1, 4)
                points = np.array(s.points, dtype=np.float64).reshape(-1, 3)
                return Snapshot(event.job_id, s.iteration, points, None, s.has_tetrahedra,
                                self._tetrahedra)
            if s.has_triangles:
                self._triangles = np.array(s.triangles, dtype=np.int32).reshape(-1, 3)
            points = np.array(s.points, dtype=np.float64).reshape(-1, 2)
            return Snapshot(event.job_id, s.iteration, points, self._triangles, s.has_triangles)
        if kind == "result_chunk":
            self._add_chunk(event.result_chunk)
            return None
        if kind == "done":
            self.done = Done(event.job_id, self._assemble(event.done))
            return self.done
        return None  # an event kind newer than these stubs

    def finish(self):
        """Checks that the stream delivered its result; raises BadResult if not."""
        if self.done is None:
            raise BadResult(f"the stream of job {self.job_id or '?'} ended without a done event")
        return self.done

    def _add_chunk(self, chunk):
        # Chunks arrive in order; check it rather than trust it.
        if chunk.index != len(self._chunks) or chunk.offset != self._received:
            raise BadResult(f"result chunk {chunk.index} (offset {chunk.offset}) arrived as "
                            f"number {len(self._chunks)} (offset {self._received})")
        self._chunks.append(chunk.data)
        self._received += len(chunk.data)

    def _assemble(self, done):
        payload = b"".join(self._chunks)
        self._chunks = []
        digest = hashlib.sha256(payload).hexdigest()
        if len(payload) != done.result_bytes or digest != done.result_sha256:
            raise BadResult(f"the result of job {self.job_id} has {len(payload)} bytes with "
                            f"SHA-256 {digest}; the server sent {done.result_bytes} bytes with "
                            f"{done.result_sha256}")
        data = mesh_pb2.MeshData.FromString(payload)
        return mesh_from_proto(data, done, job_id=self.job_id)
