#include "core/distmesh/refine.h"

#include <algorithm>
#include <cmath>

#include "core/geometry/projection.cuh"
#include "core/geometry/size_eval.cuh"

namespace meshd {
namespace {

// An edge is split when it is longer than this many times the finer level's edge at its midpoint
// (h0 h): halving it then brings it nearer that length, in ratio, than keeping it.
constexpr double kSplitAbove = M_SQRT2;

// The triangles that cover triangle (a, b, c) once the edges with a midpoint (m[k] >= 0 for edge
// k, from corner k to corner k + 1) are split, in the parent's orientation.
void split_triangle(const std::vector<Vec2>& points, std::array<int32_t, 3> t,
                    std::array<int32_t, 3> m, std::vector<std::array<int32_t, 3>>& out) {
  const int splits = (m[0] >= 0) + (m[1] >= 0) + (m[2] >= 0);
  if (splits == 0) {
    out.push_back(t);
    return;
  }
  if (splits == 3) {
    out.push_back({t[0], m[0], m[2]});
    out.push_back({m[0], t[1], m[1]});
    out.push_back({m[2], m[1], t[2]});
    out.push_back({m[0], m[1], m[2]});
    return;
  }
  // Turn the corners so that edge 0 is split and, with two splits, edge 1 too.
  const int first = splits == 1 ? (m[0] >= 0 ? 0 : m[1] >= 0 ? 1 : 2)
                                : (m[0] < 0 ? 1 : m[1] < 0 ? 2 : 0);
  std::rotate(t.begin(), t.begin() + first, t.end());
  std::rotate(m.begin(), m.begin() + first, m.end());
  const auto [a, b, c] = t;
  if (splits == 1) {
    out.push_back({a, m[0], c});
    out.push_back({m[0], b, c});
    return;
  }
  // Corner b is cut off; the quadrilateral a, m0, m1, c left takes its shorter diagonal.
  out.push_back({m[0], b, m[1]});
  const double via_a = norm(points[m[1]] - points[a]), via_c = norm(points[m[0]] - points[c]);
  if (via_a <= via_c) {
    out.push_back({a, m[0], m[1]});
    out.push_back({a, m[1], c});
  } else {
    out.push_back({a, m[0], c});
    out.push_back({m[0], m[1], c});
  }
}

}  // namespace

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
  std::vector<Edge> unique;              // each edge once, increasing
  std::vector<int32_t> midpoint_of;      // its midpoint's index, -1 where it is not split
  unique.reserve(edges.size() / 2 + 1);
  midpoint_of.reserve(edges.size() / 2 + 1);
  for (size_t i = 0; i < edges.size();) {
    size_t j = i + 1;
    while (j < edges.size() && edges[j] == edges[i]) ++j;
    const Vec2 a = points[edges[i][0]], b = points[edges[i][1]];
    Vec2 mid = 0.5 * (a + b);
    int32_t index = -1;
    if (norm(b - a) > kSplitAbove * problem.h0 * eval_size(fh, mid)) {
      if (j - i == 1) mid = project_to_boundary(fd, mid, deps);
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
  for (const auto& t : triangles)
    split_triangle(points, t, {midpoint(t[0], t[1]), midpoint(t[1], t[2]), midpoint(t[2], t[0])},
                   refined);
  return refined;
}

}  // namespace meshd
