// How far inside the domain a node is known to lie, carried from step to step, so that the
// engines evaluate the distance only near the boundary. Shared by the CPU and GPU engines.
//
// A move of length s changes the distance d by at most L s (CompiledProblem::lipschitz). A node's
// clearance starts at -d where d was evaluated, and each step lowers it by L times the step.
// While it exceeds every threshold the step compares d with (inside by more than geps: an
// interior move; by more than the near-boundary band: not on the boundary; d > 0: projection),
// d's own value changes nothing, so the evaluation is skipped and the mesh is bit for bit the
// one it would be. On a coastline, whose distance walks a tree over thousands of shoreline
// segments, most nodes lie that far inside at most steps. The nodes' clearances also decide most
// triangles' centroid test (d < -geps) without an evaluation.
#pragma once

#include <cmath>

#include "core/common/hd.h"
#include "core/common/vec2.h"

namespace meshd {

// Clearances are stored as floats, half a double's memory traffic, rounded down so that each
// stays a lower bound.
MESHD_HD inline float round_down_to_float(double x) {
#ifdef __CUDA_ARCH__
  return __double2float_rd(x);
#else
  const float f = static_cast<float>(x);
  return static_cast<double>(f) > x ? std::nextafter(f, -INFINITY) : f;
#endif
}

// No member initialisers: the rule travels in the step's arguments, which live in shared memory.
struct ClearanceRule {
  double lipschitz;  // of the distance; infinite: every node is evaluated
  double threshold;  // a clearance decides the tests only above this

  // For the tests against geps and the near-boundary band, with a margin of 1e-6 h0 that covers
  // the distance's own rounding at coordinates up to 1e9 times h0.
  static ClearanceRule make(double lipschitz, double geps, double near_boundary, double h0) {
    return {lipschitz, fmax(geps, near_boundary) + 1e-6 * h0};
  }

  // The clearance after a move of length `moved` from where it was `clearance`.
  MESHD_HD double carried(float clearance, double moved) const {
    return clearance - lipschitz * moved;
  }
  MESHD_HD bool decides(double clearance) const { return clearance > threshold; }

  // Whether the centroid g of a triangle with nodes v[k] of clearances c[k] lies inside by more
  // than the threshold (so d(g) < -geps), known without evaluating d there.
  MESHD_HD bool centroid_inside(const float c[3], const Vec2 v[3], Vec2 g) const {
    for (int k = 0; k < 3; ++k)
      if (decides(carried(c[k], norm(g - v[k])))) return true;
    return false;
  }
};

}  // namespace meshd
