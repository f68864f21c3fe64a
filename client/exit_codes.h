// meshctl's exit codes, one per kind of outcome a script may act on.
#pragma once

#include <grpcpp/support/status_code_enum.h>

namespace meshd::cli {

enum ExitCode : int {
  kExitOk = 0,
  kExitFailed = 1,              // the job failed on the server (INTERNAL), or anything else
  kExitBadRequest = 2,          // INVALID_ARGUMENT, or a bad command line
  kExitUnavailable = 3,         // no server there, queue full, or shutting down (UNAVAILABLE)
  kExitDeadline = 4,            // DEADLINE_EXCEEDED
  kExitCancelled = 5,           // CANCELLED
  kExitTooLarge = 6,            // RESOURCE_EXHAUSTED
  kExitNotFound = 7,            // NOT_FOUND (no such job)
  kExitUnauthenticated = 8,     // UNAUTHENTICATED or PERMISSION_DENIED
  kExitFailedPrecondition = 9,  // FAILED_PRECONDITION (a GPU asked of a server without one)
  kExitNotServing = 10,         // health: the server answers but is not serving
  kExitBadResult = 11,          // the result did not match its checksum, or a file failed
};

ExitCode exit_code_for(grpc::StatusCode code);

// "INVALID_ARGUMENT" and the like.
const char* status_code_name(grpc::StatusCode code);

}  // namespace meshd::cli
