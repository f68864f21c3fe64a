// Point sets and folds for the tests of completions and fold repair, on the host and the device.
#pragma once

#include <cstdint>
#include <random>
#include <vector>

#include "core/common/vec2.h"
#include "core/delaunay/delaunay.h"

namespace meshd::testing {

// A jittered triangular lattice of side^2 points: in general position, so the Delaunay
// triangulation is unique.
inline std::vector<Vec2> jittered_lattice(int side, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> jitter(-0.2, 0.2);
  std::vector<Vec2> points;
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x)
      points.push_back({x + 0.5 * (y & 1) + jitter(rng), 0.866 * y + jitter(rng)});
  return points;
}

// Moves node v across the edge opposite it in one of its triangles, to the middle of the
// triangle beyond: the triangulation now has a fold there. Returns false when v has no such
// neighbour (it lies on the hull).
inline bool push_across(const Triangulation& tri, int32_t v, std::vector<Vec2>& points) {
  for (size_t t = 0; t < tri.triangles.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      if (tri.triangles[t][k] != v || tri.neighbors[t][k] < 0) continue;
      const auto& u = tri.triangles[tri.neighbors[t][k]];
      points[v] = (1.0 / 3.0) * (points[u[0]] + points[u[1]] + points[u[2]]);
      return true;
    }
  }
  return false;
}

}  // namespace meshd::testing
