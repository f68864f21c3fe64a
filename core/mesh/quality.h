// Element quality: the radius ratio q = 2 r_in / R_circ (simpqual.m), 1 for an equilateral
// triangle and 0 for a degenerate one, and the smallest interior angle.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/mesh/mesh.h"
#include "core/mesh/min_angle.cuh"
#include "core/mesh/radius_ratio.cuh"

namespace meshd {

// Per-triangle radius ratio, #M.
std::vector<double> triangle_quality(const Mesh& mesh);

constexpr int kQualityBins = 10;

struct QualityStats {
  double q_min = 0.0;
  double q_mean = 0.0;
  double min_angle_deg = 0.0;
  // histogram[k] counts triangles with q in [k/10, (k+1)/10); q = 1 lands in the last bin.
  std::array<int64_t, kQualityBins> histogram{};
};

QualityStats summarize_quality(const Mesh& mesh);

}  // namespace meshd
