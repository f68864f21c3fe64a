// Orientation and in-circle tests with Shewchuk's static error bounds (stage A of his adaptive
// predicates), on the host and the device: +1 or -1 when the bound makes the sign certain, 0 when
// it cannot decide; the caller then defers to an exact predicate (exact_orientation.cuh, or
// exact_predicates.h on the host). nvcc compiles the kernels without fused multiply-adds
// (kernels/CMakeLists.txt), which the bounds assume.
#pragma once

#include <cmath>

#include "core/common/hd.h"
#include "core/common/vec2.h"

namespace meshd {

// +1 / -1 when certain, 0 when the filter cannot decide.
MESHD_HD inline int orientation_filtered(Vec2 a, Vec2 b, Vec2 c) {
  constexpr double kEps = 1.1102230246251565e-16;  // 2^-53
  constexpr double kBound = (3.0 + 16.0 * kEps) * kEps;
  const double left = (a.x - c.x) * (b.y - c.y);
  const double right = (a.y - c.y) * (b.x - c.x);
  const double det = left - right;
  const double bound = kBound * (fabs(left) + fabs(right));
  if (det > bound) return 1;
  if (-det > bound) return -1;
  return 0;
}

// +1 when d is certainly inside the circle through counter-clockwise a, b, c; -1 certainly
// outside; 0 undecided.
MESHD_HD inline int in_circle_filtered(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
  constexpr double kEps = 1.1102230246251565e-16;
  constexpr double kBound = (10.0 + 96.0 * kEps) * kEps;
  const double adx = a.x - d.x, ady = a.y - d.y;
  const double bdx = b.x - d.x, bdy = b.y - d.y;
  const double cdx = c.x - d.x, cdy = c.y - d.y;
  const double bdxcdy = bdx * cdy, cdxbdy = cdx * bdy;
  const double alift = adx * adx + ady * ady;
  const double cdxady = cdx * ady, adxcdy = adx * cdy;
  const double blift = bdx * bdx + bdy * bdy;
  const double adxbdy = adx * bdy, bdxady = bdx * ady;
  const double clift = cdx * cdx + cdy * cdy;
  const double det =
      alift * (bdxcdy - cdxbdy) + blift * (cdxady - adxcdy) + clift * (adxbdy - bdxady);
  const double permanent = (fabs(bdxcdy) + fabs(cdxbdy)) * alift +
                           (fabs(cdxady) + fabs(adxcdy)) * blift +
                           (fabs(adxbdy) + fabs(bdxady)) * clift;
  const double bound = kBound * permanent;
  if (det > bound) return 1;
  if (-det > bound) return -1;
  return 0;
}

}  // namespace meshd
