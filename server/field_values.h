// Checks of single request fields shared by the conversion layer's files: each throws
// Error(kInvalidArgument) naming `field` and showing the value as the user wrote it.
#pragma once

#include <string>

#include "core/common/vec2.h"
#include "meshd/v1/geometry.pb.h"

namespace meshd {

// v as shortest round-trip text ("nan", "inf" and "-inf" included).
std::string num(double v);
// " (got v)", the end of most messages.
std::string got(double v);

double finite(double v, const std::string& field);
double positive(double v, const std::string& field);        // finite and > 0
Vec2 to_vec2(const v1::Vec2& v, const std::string& field);  // both coordinates finite

}  // namespace meshd
