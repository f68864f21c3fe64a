// The one evaluator of a compiled 3D size field (size_field3.h), compiled by g++ for the CPU
// engine and by nvcc for the GPU engine: h(p) = min(uniform, min over the distance terms of
// min(h_max, h_min + slope |d(p)|)), divided by `divisor`.
#pragma once

#include <cmath>
#include <cstdint>

#include "core/common/hd.h"
#include "core/common/vec3.h"
#include "core/geometry3d/program3d.h"
#include "core/geometry3d/sdf3_eval.cuh"

namespace meshd {

struct DistanceSizeView3 {
  Program3View program;
  double h_min, slope, h_max;
};

// Trivially copyable view of a compiled size field, passed by value to device code.
struct SizeField3View {
  const DistanceSizeView3* terms;
  uint32_t count;
  double uniform;  // the uniform terms' minimum; INFINITY when there is none
  double divisor;  // > 0
};

MESHD_HD inline double eval_size3(const SizeField3View& field, Vec3 p) {
  double h = field.uniform;
  for (uint32_t i = 0; i < field.count; ++i) {
    const DistanceSizeView3& t = field.terms[i];
    const double graded = t.h_min + t.slope * fabs(eval_sdf3(t.program, p));
    const double term = graded < t.h_max ? graded : t.h_max;
    h = term < h ? term : h;
  }
  return h / field.divisor;
}

}  // namespace meshd
