#include "core/distmesh/cleanup.h"

#include <algorithm>

#include "core/distmesh/boundary_sliver.cuh"
#include "core/distmesh/engine.h"
#include "core/geometry/sdf_eval.cuh"

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
    if (!is_sliver(a, b, c)) continue;
    if (!boundary(t[0]) || !boundary(t[1]) || !boundary(t[2])) continue;
    const int k = largest_angle_corner(a, b, c);
    if (t[k] >= nfix) victims.push_back(t[k]);
  }
  std::sort(victims.begin(), victims.end());
  victims.erase(std::unique(victims.begin(), victims.end()), victims.end());
  return victims;
}

int64_t Engine::remove_boundary_slivers(const CompiledProblem& problem, int64_t max_removed) {
  std::vector<Vec2> points;
  std::vector<std::array<int32_t, 3>> triangles;
  read_points(points);
  read_triangles(triangles);
  const std::vector<int32_t> victims = cleanup_victims(problem, points, triangles);
  if (static_cast<int64_t>(victims.size()) > max_removed) return 0;
  if (!victims.empty()) remove_points(victims);
  return static_cast<int64_t>(victims.size());
}

}  // namespace meshd
