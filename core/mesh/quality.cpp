#include "core/mesh/quality.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

namespace meshd {

std::vector<double> triangle_quality(const Mesh& mesh) {
  std::vector<double> q(mesh.triangles.size());
  for (size_t i = 0; i < mesh.triangles.size(); ++i) {
    const auto& t = mesh.triangles[i];
    q[i] = radius_ratio(mesh.points[t[0]], mesh.points[t[1]], mesh.points[t[2]]);
  }
  return q;
}

QualityStats summarize_quality(const Mesh& mesh) {
  QualityStats s;
  if (mesh.triangles.empty()) return s;
  s.q_min = std::numeric_limits<double>::infinity();
  s.min_angle_deg = 180.0;
  double sum = 0.0;
  // The smallest angle of a triangle lies between its two longest sides, so its sine is twice
  // the area over their product: a cheap key that orders triangles by smallest angle up to
  // rounding. Three atan2 per triangle are then needed only near the smallest key: the
  // candidates are the triangles within the tolerance of the smallest key seen so far, a
  // superset of those near the final one, pruned whenever they have doubled.
  auto near = [](double min_sine) { return min_sine * (1.0 + 1e-6) + 1e-300; };
  std::vector<std::pair<double, size_t>> candidates;  // (sine, triangle)
  size_t prune_at = 64;
  double min_sine = INFINITY;
  for (size_t i = 0; i < mesh.triangles.size(); ++i) {
    const auto& t = mesh.triangles[i];
    const Vec2 a = mesh.points[t[0]], b = mesh.points[t[1]], c = mesh.points[t[2]];
    const double la = norm(b - c), lb = norm(c - a), lc = norm(a - b);
    const double q = radius_ratio_of_sides(la, lb, lc);
    s.q_min = std::min(s.q_min, q);
    sum += q;
    const double shortest = std::min({la, lb, lc});
    const double longest_two = la * lb * lc / shortest;
    const double sine = shortest > 0.0 ? std::fabs(cross(b - a, c - a)) / longest_two : 0.0;
    const int bin = std::clamp(static_cast<int>(q * kQualityBins), 0, kQualityBins - 1);
    ++s.histogram[bin];
    if (sine > near(min_sine)) continue;
    min_sine = std::min(min_sine, sine);
    candidates.emplace_back(sine, i);
    if (candidates.size() < prune_at) continue;
    std::erase_if(candidates, [&](const auto& e) { return e.first > near(min_sine); });
    prune_at = std::max(prune_at, 2 * candidates.size());
  }
  for (const auto& [sine, i] : candidates) {
    if (sine > near(min_sine)) continue;
    const auto& t = mesh.triangles[i];
    s.min_angle_deg = std::min(
        s.min_angle_deg, min_angle_deg(mesh.points[t[0]], mesh.points[t[1]], mesh.points[t[2]]));
  }
  s.q_mean = sum / static_cast<double>(mesh.triangles.size());
  return s;
}

}  // namespace meshd
