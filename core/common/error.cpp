#include "core/common/error.h"

#include <cstdio>

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

namespace {
constexpr size_t kMaxQuotedChars = 64;
}  // namespace

std::string quote_input(std::string_view text) {
  std::string quoted = "'";
  for (size_t i = 0; i < text.size() && i < kMaxQuotedChars; ++i) {
    const auto byte = static_cast<unsigned char>(text[i]);
    if (byte >= 0x20 && byte < 0x7f && byte != '\\') {
      quoted += text[i];
    } else {
      char escaped[8];
      std::snprintf(escaped, sizeof escaped, "\\x%02x", byte);
      quoted += escaped;
    }
  }
  quoted += "'";
  if (text.size() > kMaxQuotedChars) {
    quoted += " (the first " + std::to_string(kMaxQuotedChars) + " of " +
              std::to_string(text.size()) + " characters)";
  }
  return quoted;
}

void throw_invalid(const std::string& field, const std::string& message) {
  throw Error(ErrorCode::kInvalidArgument, field, message);
}

}  // namespace meshd
