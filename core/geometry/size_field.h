// The relative size field h(p): the desired edge length at p is h0 * h(p). Only ratios of h
// matter to DistMesh (L0 is rescaled every iteration), but keeping h near 1 where the mesh is
// finest makes h0 the smallest edge length, which users find natural.
#pragma once

#include <variant>
#include <vector>

#include "core/geometry/shape.h"

namespace meshd {

struct UniformSize {
  double value = 1.0;  // > 0
};

// h(p) = min(h_max, h_min + slope * |d(p)|), d the signed distance to `shape`.
struct DistanceSize {
  Shape shape;
  double h_min = 1.0;  // > 0
  double slope = 0.0;  // >= 0, relative size per unit length
  double h_max = 1.0;  // >= h_min
};

// h(p) = min over terms; no terms means uniform 1.
struct SizeFieldSpec {
  std::vector<std::variant<UniformSize, DistanceSize>> terms;
};

}  // namespace meshd
