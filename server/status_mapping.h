// The one place where core's errors become gRPC statuses.
#pragma once

#include <grpcpp/support/status.h>

#include <exception>

#include "core/common/error.h"

namespace meshd {

grpc::StatusCode to_grpc_code(ErrorCode code);

// The status for `error`: its code, and its message with the field path in front.
grpc::Status to_grpc_status(const Error& error);

// The status for whatever `error` holds: an Error maps by its code, anything else is INTERNAL
// (our fault) with its what().
grpc::Status to_grpc_status(const std::exception_ptr& error);

}  // namespace meshd
