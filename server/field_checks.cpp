#include "server/field_checks.h"

#include <charconv>
#include <cmath>

#include "core/common/error.h"

namespace meshd {

std::string num(double v) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, v);
  return std::string(buffer, result.ptr);
}

std::string got(double v) { return " (got " + num(v) + ")"; }

std::string at(const std::string& path, const char* field, int index) {
  return path + "." + field + "[" + std::to_string(index) + "]";
}

double finite(double v, const std::string& field) {
  if (!std::isfinite(v)) throw_invalid(field, "must be finite" + got(v));
  return v;
}

double positive(double v, const std::string& field) {
  if (!(std::isfinite(v) && v > 0)) throw_invalid(field, "must be finite and > 0" + got(v));
  return v;
}

Vec2 to_vec2(const v1::Vec2& v, const std::string& field) {
  return {finite(v.x(), field + ".x"), finite(v.y(), field + ".y")};
}

}  // namespace meshd
