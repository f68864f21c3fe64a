#include "server/field_checks.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <string>

#include "core/common/error.h"
#include "core/mesh/physical_groups.h"

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

// An estimate or a suggestion: 3 significant digits, whole numbers from 100 up.
std::string approx(double v) {
  if (std::isfinite(v) && std::fabs(v) >= 100 && std::fabs(v) < 1e18) {
    return std::to_string(std::llround(v));
  }
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.3g", v);
  return buffer;
}

namespace {

constexpr size_t kMaxNameLength = 64;

bool name_char(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
         c == '-' || c == '.';
}

// A boundary group's name: 1 to 64 letters, digits, '_', '-' or '.', not the domain's own
// group name; Error(kInvalidArgument) naming `field` otherwise.
void check_name(const std::string& name, const std::string& field) {
  const std::string allowed = "; a name is 1 to 64 letters, digits, '_', '-' or '.'";
  // The output files name the domain's own physical group so; a boundary group may not.
  if (name == kDomainGroupName) {
    throw_invalid(field, "\"" + name + "\" is reserved for the domain's own group" + allowed +
                             ", other than \"" + kDomainGroupName + "\"");
  }
  if (name.size() > kMaxNameLength) {
    throw_invalid(field, "is " + std::to_string(name.size()) + " characters long" + allowed);
  }
  for (size_t i = 0; i < name.size(); ++i) {
    if (name_char(name[i])) continue;
    // Printable characters are shown as they are; anything else by its byte value.
    const auto byte = static_cast<unsigned char>(name[i]);
    char shown[8];
    if (byte >= 0x20 && byte < 0x7f) {
      shown[0] = '\'', shown[1] = name[i], shown[2] = '\'', shown[3] = '\0';
    } else {
      std::snprintf(shown, sizeof shown, "0x%02x", byte);
    }
    throw_invalid(field,
                  "character " + std::to_string(i) + " (" + shown + ") is not allowed" + allowed);
  }
}

}  // namespace

// A term's h_max: finite and at least its h_min.
double at_least_h_min(double h_max, double h_min, const std::string& field) {
  if (!(std::isfinite(h_max) && h_max >= h_min))
    throw_invalid(field, "must be finite and >= h_min = " + num(h_min) + got(h_max));
  return h_max;
}

// Checks lo < v <= hi (lo_open) or lo <= v <= hi; NaN fails either.
double in_range(double v, double lo, bool lo_open, double hi, const std::string& field) {
  const bool ok = (lo_open ? v > lo : v >= lo) && v <= hi;
  if (!ok) {
    throw_invalid(field, std::string("must be in ") + (lo_open ? "(" : "[") + num(lo) + ", " +
                             num(hi) + "]" + got(v));
  }
  return v;
}

int in_range(uint32_t v, uint32_t lo, uint32_t hi, const std::string& field) {
  if (v < lo || v > hi) {
    throw_invalid(field, "must be in [" + std::to_string(lo) + ", " + std::to_string(hi) +
                             "] (got " + std::to_string(v) + ")");
  }
  return static_cast<int>(v);
}

void TreeBudget::enter(const std::string& path, int depth, const std::string& name) {
  if (depth > max_depth_) {
    throw_invalid(path, "the tree is deeper than the limit of " + std::to_string(max_depth_) +
                            " levels (a lone primitive is 1 level)");
  }
  if (++nodes_ > max_nodes_) {
    throw_invalid(root_, "the tree has more than the limit of " + std::to_string(max_nodes_) +
                             " shape nodes");
  }
  if (!name.empty()) check_name(name, path + ".name");
}

}  // namespace meshd
