// Uniform random points in the cube [-1, 1]^3, the same for the same seed: what the 3D
// triangulation tests start from.
#pragma once

#include <cstdint>
#include <random>
#include <vector>

#include "core/common/vec3.h"

namespace meshd::testing {

inline std::vector<Vec3> random_points3(size_t n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Vec3> points(n);
  for (Vec3& p : points) p = {u(rng), u(rng), u(rng)};
  return points;
}

}  // namespace meshd::testing
