#include "core/distmesh/refine.h"

#include <algorithm>

#include "core/geometry/projection.cuh"

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
  const auto first_midpoint = static_cast<int32_t>(points.size());
  std::vector<Edge> unique;  // the edge of midpoint first_midpoint + i
  unique.reserve(edges.size() / 2 + 1);
  for (size_t i = 0; i < edges.size();) {
    size_t j = i + 1;
    while (j < edges.size() && edges[j] == edges[i]) ++j;
    Vec2 mid = 0.5 * (points[edges[i][0]] + points[edges[i][1]]);
    if (j - i == 1) mid = project_to_boundary(fd, mid, deps);
    points.push_back(mid);
    unique.push_back(edges[i]);
    i = j;
  }
  auto midpoint = [&](int32_t a, int32_t b) {
    const auto it = std::lower_bound(unique.begin(), unique.end(), edge(a, b));
    return first_midpoint + static_cast<int32_t>(it - unique.begin());
  };
  // Corner triangles keep the parent's orientation, and so does the middle one.
  std::vector<std::array<int32_t, 3>> refined;
  refined.reserve(4 * triangles.size());
  for (const auto& t : triangles) {
    const int32_t a = t[0], b = t[1], c = t[2];
    const int32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
    refined.push_back({a, ab, ca});
    refined.push_back({ab, b, bc});
    refined.push_back({ca, bc, c});
    refined.push_back({ab, bc, ca});
  }
  return refined;
}

}  // namespace meshd
