#include "core/distmesh/cleanup.h"

#include <algorithm>

#include "core/geometry/sdf_eval.cuh"
#include "core/mesh/quality.h"

namespace meshd {

std::vector<int32_t> cleanup_victims(const CompiledProblem& problem,
                                     const std::vector<Vec2>& points,
                                     const std::vector<std::array<int32_t, 3>>& triangles) {
  const double geps = problem.params.geps * problem.h0;
  const auto nfix = static_cast<int32_t>(problem.fixed_points.size());
  std::vector<signed char> on_boundary(points.size(), -1);  // -1 unknown, 0 no, 1 yes
  auto boundary = [&](int32_t i) {
    if (on_boundary[i] < 0) on_boundary[i] = eval_sdf(problem.geometry.view(), points[i]) > -geps;
    return on_boundary[i] == 1;
  };
  std::vector<int32_t> victims;
  for (const auto& t : triangles) {
    const Vec2 a = points[t[0]], b = points[t[1]], c = points[t[2]];
    if (radius_ratio(a, b, c) >= kSliverQuality) continue;
    if (!boundary(t[0]) || !boundary(t[1]) || !boundary(t[2])) continue;
    // The obtuse corner is opposite the longest side.
    const double la = norm(b - c), lb = norm(c - a), lc = norm(a - b);
    const int k = la >= lb && la >= lc ? 0 : (lb >= lc ? 1 : 2);
    if (t[k] >= nfix) victims.push_back(t[k]);
  }
  std::sort(victims.begin(), victims.end());
  victims.erase(std::unique(victims.begin(), victims.end()), victims.end());
  return victims;
}

}  // namespace meshd
