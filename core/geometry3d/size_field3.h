// The relative size field of a 3D request, h(p): the desired edge length at p is h0 * h(p),
// the minimum of its terms (uniform 1 when there are none), as in 2D (size_field.h).
#pragma once

#include <cmath>
#include <functional>
#include <memory>
#include <variant>
#include <vector>

#include "core/common/vec3.h"
#include "core/geometry/size_field.h"  // UniformSize, shared with 2D
#include "core/geometry3d/program3d.h"
#include "core/geometry3d/shape3d.h"
#include "core/geometry3d/size_field3_eval.cuh"

namespace meshd {

// h(p) = min(h_max, h_min + slope * |d(p)|), d the signed distance to `shape`.
struct DistanceSize3 {
  Shape3 shape;
  double h_min = 1.0;  // > 0
  double slope = 0.0;  // >= 0, relative size per unit length
  double h_max = 1.0;  // >= h_min
};

using SizeTerm3 = std::variant<UniformSize, DistanceSize3>;

struct SizeField3 {
  std::vector<SizeTerm3> terms;
};

// The smallest and largest value `field` takes anywhere (its terms' bounds); {1, 1} when empty.
SizeRange size_range3(const SizeField3& field);

// A size field compiled for its evaluator (size_field3_eval.cuh): the uniform terms folded into
// one value, each distance term's shape compiled. `divisor` (> 0) divides every value, so that h
// is relative to its smallest bound where the loop wants it so.
struct CompiledSizeField3 {
  double uniform = INFINITY;
  struct Term {
    Program3 program;
    double h_min, slope, h_max;
  };
  std::vector<Term> terms;
  double divisor = 1.0;
  // Views into `terms`, refreshed by compile; the field must not move afterwards.
  std::vector<DistanceSizeView3> views;

  SizeField3View view() const {
    return {views.data(), static_cast<uint32_t>(views.size()), uniform, divisor};
  }
};

// Compiles `field`, with every value divided by `divisor`. Throws Error(kInvalidArgument) naming
// the field of a distance term's bad shape.
std::shared_ptr<const CompiledSizeField3> compile_size_field3(const SizeField3& field,
                                                              double divisor);

// h as a callable over `field`; empty for no terms (a uniform field), which the loop treats as
// h = 1. The callable shares `field`, so copies are cheap.
std::function<double(Vec3)> size_callable3(std::shared_ptr<const CompiledSizeField3> field,
                                           bool uniform);

// Both at once, divisor 1 (what the checks of a request use).
std::function<double(Vec3)> compile_size_field3(const SizeField3& field);

}  // namespace meshd
