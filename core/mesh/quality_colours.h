// The colour map of the pictures (svg_writer.h, svg_surface3d.h): element quality from dark red
// (degenerate) through red, orange, yellow and green to blue (equilateral).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>

namespace meshd {

struct Rgb {
  double r, g, b;
};

inline Rgb quality_colour(double q) {
  static constexpr std::array<std::pair<double, Rgb>, 7> kStops = {{{0.0, {165, 0, 38}},
                                                                    {0.3, {215, 48, 39}},
                                                                    {0.5, {253, 174, 97}},
                                                                    {0.7, {254, 224, 139}},
                                                                    {0.85, {166, 217, 106}},
                                                                    {0.95, {26, 152, 80}},
                                                                    {1.0, {49, 54, 149}}}};
  q = std::clamp(q, 0.0, 1.0);
  size_t k = 1;
  while (k + 1 < kStops.size() && q > kStops[k].first) ++k;
  const auto& [q0, c0] = kStops[k - 1];
  const auto& [q1, c1] = kStops[k];
  const double s = (q - q0) / (q1 - q0);
  return {c0.r + s * (c1.r - c0.r), c0.g + s * (c1.g - c0.g), c0.b + s * (c1.b - c0.b)};
}

inline std::string hex(Rgb c) {
  char s[8];
  std::snprintf(s, sizeof(s), "#%02x%02x%02x", static_cast<int>(std::lround(c.r)),
                static_cast<int>(std::lround(c.g)), static_cast<int>(std::lround(c.b)));
  return s;
}

}  // namespace meshd
