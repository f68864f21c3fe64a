// The one size-field evaluator, shared by the CPU and GPU engines.
#pragma once

#include "core/geometry/regular_grid.h"
#include "core/geometry/sdf_eval.cuh"
#include "core/geometry/size_program.h"

namespace meshd {

// Relative size h(p) > 0.
MESHD_HD inline double eval_size(SizeView size, Vec2 p) {
  if (size.count == 0) return 1.0;
  double h = INFINITY;
  for (uint32_t i = 0; i < size.count; ++i) {
    const SizeTermCode t = size.terms[i];
    double term = t.h_min;
    if (t.grid != kNoGrid) {
      term = t.scale * bilinear(grid_at(size.shapes.params, size.shapes.samples, t.grid), p);
    } else if (t.begin != t.end) {
      const double d = eval_sdf_range(size.shapes, t.begin, t.end, p);
      term = min2(t.h_max, t.h_min + t.slope * fabs(d));
    }
    h = min2(h, term);
  }
  return h;
}

}  // namespace meshd
