#include "core/distmesh3d/node_estimate3d.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace meshd {

namespace {

// Nodes per unit volume of the body-centred start with edges of 1.
constexpr double kNodesPerVolume = 1.4142135623730951;

}  // namespace

VolumeSurvey3 survey_volume3d(const std::function<double(Vec3)>& distance,
                              const std::function<double(Vec3)>& size, const Box3& b) {
  constexpr int kCells = 32;
  const Vec3 step{(b.max.x - b.min.x) / kCells, (b.max.y - b.min.y) / kCells,
                  (b.max.z - b.min.z) / kCells};
  std::vector<double> sizes;
  double h_min = INFINITY;
  VolumeSurvey3 out;
  out.half_diagonal = 0.5 * std::sqrt(dot(step, step));
  for (int k = 0; k < kCells; ++k)
    for (int j = 0; j < kCells; ++j)
      for (int i = 0; i < kCells; ++i) {
        const Vec3 p{b.min.x + (i + 0.5) * step.x, b.min.y + (j + 0.5) * step.y,
                     b.min.z + (k + 0.5) * step.z};
        const double d = distance(p);
        if (!(d < 0.0)) continue;
        out.depth = std::max(out.depth, -d);
        const double h = size ? size(p) : 1.0;
        sizes.push_back(h);
        h_min = std::min(h_min, h);
      }
  double weighted = 0.0;
  for (double h : sizes) weighted += std::pow(h_min / h, 3.0);
  out.weighted_volume = weighted * step.x * step.y * step.z;
  return out;
}

double node_count3d(double weighted_volume, double h0) {
  return kNodesPerVolume * weighted_volume / (h0 * h0 * h0);
}

double h0_for_node_count3d(double weighted_volume, double nodes) {
  return std::cbrt(kNodesPerVolume * weighted_volume / nodes);
}

}  // namespace meshd
