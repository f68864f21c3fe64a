// The one error type that core/ throws. It carries a code chosen by meaning, the request field
// it concerns (a path such as "geometry.union.shapes[2].circle.radius", empty when none) and
// a message that states the allowed range. The service maps the code to a gRPC status in one
// place; core/ never aborts or exits.
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>

namespace meshd {

enum class ErrorCode {
  kInvalidArgument,    // the request is wrong; field() names where
  kResourceExhausted,  // the request is valid but larger than the configured limits allow
  kCancelled,          // the job's cancellation flag was set
  kDeadlineExceeded,   // the job ran out of time
  kUnavailable,        // no capacity now (queue full, shutting down)
  kFailedPrecondition, // the server cannot run it as asked (a GPU job on a server without one)
  kNotFound,           // no such job
  kInternal,           // our own fault
};

const char* error_code_name(ErrorCode code);

class Error : public std::runtime_error {
 public:
  Error(ErrorCode code, std::string field, const std::string& message);

  ErrorCode code() const { return code_; }
  const std::string& field() const { return field_; }
  // The message without the field prefix that what() carries.
  const std::string& detail() const { return detail_; }

 private:
  ErrorCode code_;
  std::string field_;
  std::string detail_;
};

// Shorthand for the most common case: an invalid request field.
[[noreturn]] void throw_invalid(const std::string& field, const std::string& message);

// `text` from a request, quoted for an error message: at most 64 characters shown, bytes that
// are not printable ASCII as \xNN, and a longer text cut with its length said, so that an echoed
// input never outgrows the status message that carries it.
std::string quote_input(std::string_view text);

}  // namespace meshd
