#include "core/distmesh/refine.h"

#include <algorithm>

#include "core/geometry/projection.cuh"

namespace meshd {

void refine_by_midpoints(const CompiledProblem& problem, std::vector<Vec2>& points,
                         const std::vector<std::array<int32_t, 3>>& triangles) {
  // Each edge as (low, high); an edge seen once is on the boundary.
  std::vector<std::array<int32_t, 2>> edges;
  edges.reserve(3 * triangles.size());
  for (const auto& t : triangles) {
    for (int k = 0; k < 3; ++k) {
      const int32_t a = t[k], b = t[(k + 1) % 3];
      edges.push_back({std::min(a, b), std::max(a, b)});
    }
  }
  std::sort(edges.begin(), edges.end());
  const double deps = problem.params.deps * problem.h0;
  const ProgramView fd = problem.geometry.view();
  for (size_t i = 0; i < edges.size();) {
    size_t j = i + 1;
    while (j < edges.size() && edges[j] == edges[i]) ++j;
    Vec2 mid = 0.5 * (points[edges[i][0]] + points[edges[i][1]]);
    if (j - i == 1) mid = project_to_boundary(fd, mid, deps);
    points.push_back(mid);
    i = j;
  }
}

}  // namespace meshd
