"""What the server says about one job (meshd.v1.JobInfo), as a Python object."""

from dataclasses import dataclass

from meshd.errors import error_code_from_int, error_for_status
from meshd.mesh import Quality, RunStats
from meshd.request import BACKEND_NAMES
from meshd.v1 import service_pb2

STATES = {service_pb2.JOB_STATE_UNSPECIFIED: "unspecified",
          service_pb2.JOB_STATE_QUEUED: "queued",
          service_pb2.JOB_STATE_RUNNING: "running",
          service_pb2.JOB_STATE_SUCCEEDED: "succeeded",
          service_pb2.JOB_STATE_FAILED: "failed",
          service_pb2.JOB_STATE_CANCELLED: "cancelled"}
STATE_VALUES = {name: value for value, name in STATES.items()}


@dataclass(frozen=True)
class JobInfo:
    """state: "queued", "running", "succeeded", "failed" or "cancelled". error: the MeshdError
    of a failed or cancelled job, else None. quality and stats: once succeeded, else None.
    Times in seconds; submitted_at in Unix time."""
    job_id: str
    state: str
    label: str
    priority: int
    queue_position: int
    backend: str
    device: str
    iteration: int
    nodes: int
    queue_wait_s: float
    run_s: float
    submitted_at: float
    error: Exception
    quality: Quality
    stats: RunStats

    @classmethod
    def from_proto(cls, info):
        error = None
        if info.error_code:
            error = error_for_status(error_code_from_int(info.error_code), info.error_message)
        done = info.done if info.HasField("done") else None
        return cls(job_id=info.job_id, state=STATES.get(info.state, "unspecified"),
                   label=info.label, priority=info.priority,
                   queue_position=info.queue_position, backend=BACKEND_NAMES.get(info.backend, ""),
                   device=info.device, iteration=info.iteration, nodes=info.nodes,
                   queue_wait_s=info.queue_wait_s, run_s=info.run_s,
                   submitted_at=info.submitted_at, error=error,
                   quality=Quality.from_proto(done.quality) if done else None,
                   stats=RunStats.from_proto(done.stats) if done else None)

    @property
    def finished(self):
        return self.state in ("succeeded", "failed", "cancelled")
