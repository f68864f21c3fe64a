#include "core/mesh3d/tet_quality.h"

#include <algorithm>
#include <limits>

namespace meshd {

std::vector<double> tet_quality(const std::vector<Vec3>& points,
                                const std::vector<std::array<int32_t, 4>>& tets) {
  std::vector<double> q(tets.size());
  for (size_t t = 0; t < tets.size(); ++t) {
    const auto& v = tets[t];
    q[t] = oriented_tet_radius_ratio(points[v[0]], points[v[1]], points[v[2]], points[v[3]]);
  }
  return q;
}

std::vector<double> tet_quality(const TetMesh& mesh) { return tet_quality(mesh.points, mesh.tets); }

TetQualityStats summarize_tet_quality(const std::vector<Vec3>& points,
                                      const std::vector<std::array<int32_t, 4>>& tets) {
  TetQualityStats s;
  if (tets.empty()) return s;
  s.q_min = std::numeric_limits<double>::infinity();
  s.min_dihedral_deg = 180.0;
  double sum = 0.0;
  for (const auto& v : tets) {
    const Vec3 a = points[v[0]], b = points[v[1]], c = points[v[2]], d = points[v[3]];
    const double q = oriented_tet_radius_ratio(a, b, c, d);
    s.q_min = std::min(s.q_min, q);
    sum += q;
    // Written so that NaN (from infinite coordinates) lands in the first bin.
    const int bin = q > 0.0 ? std::min(static_cast<int>(q * kQualityBins), kQualityBins - 1) : 0;
    ++s.histogram[bin];
    double lo = 0.0, hi = 0.0;
    tet_dihedral_range(a, b, c, d, lo, hi);
    s.min_dihedral_deg = std::min(s.min_dihedral_deg, lo);
    s.max_dihedral_deg = std::max(s.max_dihedral_deg, hi);
    s.volume += dot(b - a, cross(c - a, d - a)) / 6.0;
  }
  s.q_mean = sum / static_cast<double>(tets.size());
  return s;
}

TetQualityStats summarize_tet_quality(const TetMesh& mesh) {
  return summarize_tet_quality(mesh.points, mesh.tets);
}

}  // namespace meshd
