// What the conversion tests expect of a bad request: to_job_spec (the plane and the volume
// conversion, then the options) fails with a code, on a field, with a message that states the
// allowed range.
#pragma once

#include <gtest/gtest.h>

#include <string>

#include "core/common/error.h"
#include "server/request_conversion.h"

namespace meshd::testing {

// Converts `request` and checks that it fails with `code` on `field`, with a message containing
// `message`.
inline void expect_error(const v1::MeshRequest& request, ErrorCode code, const std::string& field,
                         const std::string& message, const ConversionLimits& limits = {}) {
  try {
    to_job_spec(request, limits);
    ADD_FAILURE() << "no error; expected " << field << ": " << message;
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), code) << e.what();
    EXPECT_EQ(e.field(), field) << e.what();
    EXPECT_NE(e.detail().find(message), std::string::npos)
        << "message: " << e.detail() << "\nexpected to contain: " << message;
  }
}

inline void expect_invalid(const v1::MeshRequest& request, const std::string& field,
                           const std::string& message, const ConversionLimits& limits = {}) {
  expect_error(request, ErrorCode::kInvalidArgument, field, message, limits);
}

}  // namespace meshd::testing
