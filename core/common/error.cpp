#include "core/common/error.h"

namespace meshd {

const char* error_code_name(ErrorCode code) {
  switch (code) {
    case ErrorCode::kInvalidArgument:
      return "INVALID_ARGUMENT";
    case ErrorCode::kResourceExhausted:
      return "RESOURCE_EXHAUSTED";
    case ErrorCode::kCancelled:
      return "CANCELLED";
    case ErrorCode::kDeadlineExceeded:
      return "DEADLINE_EXCEEDED";
    case ErrorCode::kUnavailable:
      return "UNAVAILABLE";
    case ErrorCode::kFailedPrecondition:
      return "FAILED_PRECONDITION";
    case ErrorCode::kNotFound:
      return "NOT_FOUND";
    case ErrorCode::kInternal:
      return "INTERNAL";
  }
  return "UNKNOWN";
}

Error::Error(ErrorCode code, std::string field, const std::string& message)
    : std::runtime_error(field.empty() ? message : field + ": " + message),
      code_(code),
      field_(std::move(field)),
      detail_(message) {}

void throw_invalid(const std::string& field, const std::string& message) {
  throw Error(ErrorCode::kInvalidArgument, field, message);
}

}  // namespace meshd
