// The relative size field of a 3D request, h(p): the desired edge length at p is h0 * h(p),
// the minimum of its terms (uniform 1 when there are none), as in 2D (size_field.h).
#pragma once

#include <functional>
#include <memory>
#include <variant>
#include <vector>

#include "core/common/vec3.h"
#include "core/geometry/size_field.h"  // UniformSize, shared with 2D
#include "core/geometry3d/program3d.h"
#include "core/geometry3d/shape3d.h"

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

// h as a callable over the compiled distance terms; empty for no terms (a uniform field), which
// the loop treats as h = 1. The callable shares the compiled programs, so copies are cheap.
// Throws Error(kInvalidArgument) naming the field of a distance term's bad shape.
std::function<double(Vec3)> compile_size_field3(const SizeField3& field);

}  // namespace meshd
