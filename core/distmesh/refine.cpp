#include "core/distmesh/refine.h"

#include <algorithm>
#include <cmath>

#include "core/distmesh/refine_rule.cuh"

namespace meshd {

std::vector<std::array<int32_t, 3>> refine_by_midpoints(
    const CompiledProblem& problem, std::vector<Vec2>& points,
    const std::vector<std::array<int32_t, 3>>& triangles) {
  using Edge = std::array<int32_t, 2>;
  auto edge = [](int32_t a, int32_t b) { return Edge{std::min(a, b), std::max(a, b)}; };
  // Each edge as (low, high); an edge seen once is on the boundary.
  std::vector<Edge> edges;
  edges.reserve(3 * triangles.size());
  for (const auto& t : triangles) {
    for (int k = 0; k < 3; ++k) edges.push_back(edge(t[k], t[(k + 1) % 3]));
  }
  std::sort(edges.begin(), edges.end());
  const double deps = problem.params.deps * problem.h0;
  const ProgramView fd = problem.geometry.view();
  const SizeView fh = problem.size.view();
  std::vector<Edge> unique;          // each edge once, increasing
  std::vector<int32_t> midpoint_of;  // its midpoint's index, -1 where it is not split
  unique.reserve(edges.size() / 2 + 1);
  midpoint_of.reserve(edges.size() / 2 + 1);
  for (size_t i = 0; i < edges.size();) {
    size_t j = i + 1;
    while (j < edges.size() && edges[j] == edges[i]) ++j;
    Vec2 mid;
    int32_t index = -1;
    if (split_point(fd, fh, problem.h0, deps, points[edges[i][0]], points[edges[i][1]], j - i == 1,
                    mid)) {
      index = static_cast<int32_t>(points.size());
      points.push_back(mid);
    }
    unique.push_back(edges[i]);
    midpoint_of.push_back(index);
    i = j;
  }
  auto midpoint = [&](int32_t a, int32_t b) {
    const auto it = std::lower_bound(unique.begin(), unique.end(), edge(a, b));
    return midpoint_of[static_cast<size_t>(it - unique.begin())];
  };
  std::vector<std::array<int32_t, 3>> refined;
  refined.reserve(4 * triangles.size());
  for (const auto& t : triangles) {
    const int32_t m[3] = {midpoint(t[0], t[1]), midpoint(t[1], t[2]), midpoint(t[2], t[0])};
    int32_t children[4][3];
    const int count = split_triangle(points.data(), t.data(), m, children);
    for (int k = 0; k < count; ++k)
      refined.push_back({children[k][0], children[k][1], children[k][2]});
  }
  return refined;
}

}  // namespace meshd
