// The relative size field h(p): the desired edge length at p is h0 * h(p). Only ratios of h
// matter to DistMesh (L0 is rescaled every iteration), but keeping h near 1 where the mesh is
// finest makes h0 the smallest edge length, which users find natural.
#pragma once

#include <cstdint>
#include <variant>
#include <vector>

#include "core/common/vec2.h"
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

// h(p) = scale * bilinear interpolation of samples on a regular grid (regular_grid.h), the
// border values extended outwards. Sample (i, j) lies at origin + (i * spacing.x, j * spacing.y)
// and is values[j * nx + i]. `scale` keeps sizes far from 1 within single precision.
struct GridSize {
  Vec2 origin;
  Vec2 spacing;               // > 0 in both coordinates
  uint32_t nx = 0;            // >= 2
  uint32_t ny = 0;            // >= 2
  std::vector<float> values;  // nx * ny, each finite and > 0
  double scale = 1.0;         // > 0
};

// h(p) = clamp(2 (|d(p)| + d_MA(p)) / (elements * h0), h_min, h_max): about `elements` edges
// across the domain's narrow parts, d_MA the distance to the medial axis (feature_size.h).
// Sampled on a grid over the domain before meshing (compile_problem), never compiled as it is.
struct FeatureSize {
  double elements = 2.0;  // >= 1
  double h_min = 1.0;     // > 0
  double h_max = 1.0;     // >= h_min
};

using SizeTerm = std::variant<UniformSize, DistanceSize, GridSize, FeatureSize>;

// h(p) = min over terms; no terms means uniform 1. A gradation g > 0 then limits the growth of
// the edge length, |grad(h0 h)| <= g, on a grid over the domain (gradation.h); the two are
// applied by sampled_size_field (compiled_problem.h).
struct SizeFieldSpec {
  std::vector<SizeTerm> terms;
  double gradation = 0.0;  // 0: none
};

// The smallest and the largest value a term takes anywhere.
struct SizeRange {
  double low;
  double high;
};
SizeRange size_term_range(const SizeTerm& term);

// The range of h = min over terms: [min of lows, min of highs]; [1, 1] for no terms.
SizeRange size_field_range(const SizeFieldSpec& spec);

}  // namespace meshd
