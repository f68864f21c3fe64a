"""meshd's gRPC statuses as Python exceptions.

Every failed call raises a MeshdError subclass chosen by the status code. The server puts the
field path of a bad request at the start of the status message ("field: what is wrong"), not in
the status details, so `field` is parsed from the message:

    geometry.difference.subtract[0].circle.radius: must be finite and > 0 (got -0.5)
    -> field "geometry.difference.subtract[0].circle.radius",
       reason "must be finite and > 0 (got -0.5)"

Messages that name no field ("the server is shutting down") leave `field` None.
"""

import re

import grpc

# A dotted path of identifiers, each optionally indexed: h0, job_id, options.backend,
# geometry.union.shapes[2].polygon.vertices[7].x. No spaces, so "internal error: ..." is no field.
_FIELD_PREFIX = re.compile(
    r"^([A-Za-z_][A-Za-z0-9_]*(?:\[\d+\])*(?:\.[A-Za-z_][A-Za-z0-9_]*(?:\[\d+\])*)*): (.*)$",
    re.DOTALL)


class MeshdError(Exception):
    """A call to meshd failed. code: grpc.StatusCode; message: the server's whole message;
    field: the request field it names, or None; reason: the message after the field."""

    code = grpc.StatusCode.UNKNOWN

    def __init__(self, message, code=None, field=None, reason=None):
        super().__init__(message)
        if code is not None:
            self.code = code
        self.message = message
        self.field = field
        self.reason = message if reason is None else reason

    def __str__(self):
        return f"{self.code.name}: {self.message}"


class InvalidArgument(MeshdError):
    code = grpc.StatusCode.INVALID_ARGUMENT


class NotFound(MeshdError):
    code = grpc.StatusCode.NOT_FOUND


class Unavailable(MeshdError):
    code = grpc.StatusCode.UNAVAILABLE


class DeadlineExceeded(MeshdError):
    code = grpc.StatusCode.DEADLINE_EXCEEDED


class Cancelled(MeshdError):
    code = grpc.StatusCode.CANCELLED


class ResourceExhausted(MeshdError):
    code = grpc.StatusCode.RESOURCE_EXHAUSTED


class FailedPrecondition(MeshdError):
    code = grpc.StatusCode.FAILED_PRECONDITION


class Unauthenticated(MeshdError):
    code = grpc.StatusCode.UNAUTHENTICATED


class PermissionDenied(MeshdError):
    code = grpc.StatusCode.PERMISSION_DENIED


class Internal(MeshdError):
    code = grpc.StatusCode.INTERNAL


class BadResult(MeshdError):
    """The result stream was inconsistent (chunks out of order, a wrong SHA-256, no done)."""
    code = grpc.StatusCode.DATA_LOSS


_BY_CODE = {cls.code: cls for cls in (
    InvalidArgument, NotFound, Unavailable, DeadlineExceeded, Cancelled, ResourceExhausted,
    FailedPrecondition, Unauthenticated, PermissionDenied, Internal, BadResult)}


def error_for_status(code, message):
    """The MeshdError for a status code (grpc.StatusCode) and its message."""
    message = message or ""
    match = _FIELD_PREFIX.match(message)
    field, reason = (match.group(1), match.group(2)) if match else (None, message)
    cls = _BY_CODE.get(code, MeshdError)
    return cls(message, code=code, field=field, reason=reason)


def from_rpc_error(error):
    """The MeshdError for a grpc.RpcError (sync) or grpc.aio.AioRpcError."""
    return error_for_status(error.code(), error.details())


def error_code_from_int(value):
    """grpc.StatusCode for the integer code JobInfo.error_code carries (google.rpc.Code)."""
    for code in grpc.StatusCode:
        if code.value[0] == value:
            return code
    return grpc.StatusCode.UNKNOWN
