// The smallest interior angle of a triangle, in degrees: shared by the quality summary, the VTU
// writer's cell data and the GPU engine's quality measure.
#pragma once

#include <cmath>

#include "core/common/hd.h"
#include "core/common/vec2.h"

namespace meshd {

MESHD_HD inline double min_angle_deg(Vec2 a, Vec2 b, Vec2 c) {
  auto angle = [](Vec2 apex, Vec2 u, Vec2 v) {
    return atan2(fabs(cross(u - apex, v - apex)), dot(u - apex, v - apex));
  };
  const double m = fmin(fmin(angle(a, b, c), angle(b, c, a)), angle(c, a, b));
  return m * 180.0 / M_PI;
}

}  // namespace meshd
