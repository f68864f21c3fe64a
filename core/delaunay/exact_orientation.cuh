// The exact orientation of three points, on the host and the device: the static filter of
// filtered_predicates.cuh first, then, where it cannot decide, the determinant summed exactly as
// a floating-point expansion (Shewchuk's error-free sums and products). The device's point
// insertion (parallel_insertion.cuh) locates points with it, so that a point on an edge is known
// to be on it; exact_predicates.h (CGAL) is the reference its tests hold it to.
#pragma once

#include <cmath>

#include "core/common/hd.h"
#include "core/common/vec2.h"
#include "core/delaunay/filtered_predicates.cuh"

namespace meshd {
namespace exact_detail {

// a + b = sum + err exactly.
MESHD_HD inline void two_sum(double a, double b, double& sum, double& err) {
  sum = a + b;
  const double bv = sum - a;
  const double av = sum - bv;
  err = (a - av) + (b - bv);
}

// a * b = product + err exactly (fma rounds once).
MESHD_HD inline void two_product(double a, double b, double& product, double& err) {
  product = a * b;
  err = fma(a, b, -product);
}

// Adds b to the expansion e[0..n) (non-overlapping, increasing magnitude, no zeros) in place;
// returns its new length. e has room for one more component.
MESHD_HD inline int grow_expansion(double* e, int n, double b) {
  double q = b;
  int out = 0;
  for (int i = 0; i < n; ++i) {
    double sum, err;
    two_sum(q, e[i], sum, err);
    q = sum;
    if (err != 0.0) e[out++] = err;
  }
  if (q != 0.0) e[out++] = q;
  return out;
}

}  // namespace exact_detail

// +1 when a, b, c turn counter-clockwise, -1 clockwise, 0 when exactly collinear.
MESHD_HD inline int orientation_exact(Vec2 a, Vec2 b, Vec2 c) {
  const int filtered = orientation_filtered(a, b, c);
  if (filtered != 0) return filtered;
  using namespace exact_detail;
  // det = (ax - cx)(by - cy) - (ay - cy)(bx - cx), each difference exact as two terms.
  double acx, acx_t, bcy, bcy_t, acy, acy_t, bcx, bcx_t;
  two_sum(a.x, -c.x, acx, acx_t);
  two_sum(b.y, -c.y, bcy, bcy_t);
  two_sum(a.y, -c.y, acy, acy_t);
  two_sum(b.x, -c.x, bcx, bcx_t);
  const double left[2] = {acx, acx_t}, right[2] = {bcy, bcy_t};
  const double left2[2] = {acy, acy_t}, right2[2] = {bcx, bcx_t};
  double e[17];
  int n = 0;
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) {
      double product, err;
      two_product(left[i], right[j], product, err);
      n = grow_expansion(e, n, err);
      n = grow_expansion(e, n, product);
      two_product(left2[i], right2[j], product, err);
      n = grow_expansion(e, n, -err);
      n = grow_expansion(e, n, -product);
    }
  // The largest component of a non-overlapping expansion carries its sign.
  if (n == 0) return 0;
  return e[n - 1] > 0.0 ? 1 : -1;
}

}  // namespace meshd
