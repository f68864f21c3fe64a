// The clean-up's rule for one triangle (see cleanup.h), shared by the CPU and GPU engines: a
// sliver whose three nodes all lie on the boundary loses the node at its largest angle.
#pragma once

#include "core/common/hd.h"
#include "core/common/vec2.h"
#include "core/mesh/radius_ratio.cuh"

namespace meshd {

// A boundary triangle with radius ratio under this is a sliver worth removing.
constexpr double kSliverQuality = 0.5;

MESHD_HD inline bool is_sliver(Vec2 a, Vec2 b, Vec2 c) {
  return radius_ratio(a, b, c) < kSliverQuality;
}

// The corner (0, 1 or 2) at the largest angle: the one opposite the longest side.
MESHD_HD inline int largest_angle_corner(Vec2 a, Vec2 b, Vec2 c) {
  const double la = norm(b - c), lb = norm(c - a), lc = norm(a - b);
  return la >= lb && la >= lc ? 0 : (lb >= lc ? 1 : 2);
}

}  // namespace meshd
