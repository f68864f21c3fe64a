// The pieces of the conversion layer's messages and range checks that more than one converter
// uses: the value as the user wrote it, and the checks that name the field and the allowed range.
#pragma once

#include <string>

#include "core/common/vec2.h"
#include "meshd/v1/geometry.pb.h"

namespace meshd {

// The value as the user wrote it: the shortest text that reads back as the same double.
std::string num(double v);

// " (got <num(v)>)", the tail of a range message.
std::string got(double v);

// "<path>.<field>[<index>]", the path of a repeated field's entry.
std::string at(const std::string& path, const char* field, int index);

// v, or Error(kInvalidArgument) naming `field` when it is not finite.
double finite(double v, const std::string& field);

// v, or Error(kInvalidArgument) naming `field` unless it is finite and > 0.
double positive(double v, const std::string& field);

// The point, each coordinate checked by finite() as field + ".x" and ".y".
Vec2 to_vec2(const v1::Vec2& v, const std::string& field);

}  // namespace meshd
