// Orientation and in-circle tests on the device with Shewchuk's static error bounds (stage A of
// his adaptive predicates): when |det| exceeds the bound the sign is certain; otherwise the
// caller defers to the exact host predicates (core/delaunay/exact_predicates.h). Products and
// sums use explicit round-to-nearest intrinsics so that nvcc cannot fuse them into FMAs, which
// the bounds do not account for.
#pragma once

#include "core/common/vec2.h"

namespace meshd::gpu {

// +1 / -1 when certain, 0 when the filter cannot decide.
__device__ inline int orientation_filtered(Vec2 a, Vec2 b, Vec2 c) {
  constexpr double kEps = 1.1102230246251565e-16;  // 2^-53
  constexpr double kBound = (3.0 + 16.0 * kEps) * kEps;
  const double left = __dmul_rn(__dsub_rn(a.x, c.x), __dsub_rn(b.y, c.y));
  const double right = __dmul_rn(__dsub_rn(a.y, c.y), __dsub_rn(b.x, c.x));
  const double det = __dsub_rn(left, right);
  const double bound = kBound * (fabs(left) + fabs(right));
  if (det > bound) return 1;
  if (-det > bound) return -1;
  return 0;
}

// +1 when d is certainly inside the circle through counter-clockwise a, b, c; -1 certainly
// outside; 0 undecided.
__device__ inline int in_circle_filtered(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
  constexpr double kEps = 1.1102230246251565e-16;
  constexpr double kBound = (10.0 + 96.0 * kEps) * kEps;
  const double adx = __dsub_rn(a.x, d.x), ady = __dsub_rn(a.y, d.y);
  const double bdx = __dsub_rn(b.x, d.x), bdy = __dsub_rn(b.y, d.y);
  const double cdx = __dsub_rn(c.x, d.x), cdy = __dsub_rn(c.y, d.y);
  const double bdxcdy = __dmul_rn(bdx, cdy), cdxbdy = __dmul_rn(cdx, bdy);
  const double alift = __dadd_rn(__dmul_rn(adx, adx), __dmul_rn(ady, ady));
  const double cdxady = __dmul_rn(cdx, ady), adxcdy = __dmul_rn(adx, cdy);
  const double blift = __dadd_rn(__dmul_rn(bdx, bdx), __dmul_rn(bdy, bdy));
  const double adxbdy = __dmul_rn(adx, bdy), bdxady = __dmul_rn(bdx, ady);
  const double clift = __dadd_rn(__dmul_rn(cdx, cdx), __dmul_rn(cdy, cdy));
  const double det = __dadd_rn(__dadd_rn(__dmul_rn(alift, __dsub_rn(bdxcdy, cdxbdy)),
                                         __dmul_rn(blift, __dsub_rn(cdxady, adxcdy))),
                               __dmul_rn(clift, __dsub_rn(adxbdy, bdxady)));
  const double permanent = (fabs(bdxcdy) + fabs(cdxbdy)) * alift +
                           (fabs(cdxady) + fabs(adxcdy)) * blift +
                           (fabs(adxbdy) + fabs(bdxady)) * clift;
  const double bound = kBound * permanent;
  if (det > bound) return 1;
  if (-det > bound) return -1;
  return 0;
}

}  // namespace meshd::gpu
