// Uniform random points in the cube [-1, 1]^3, the same for the same seed: what the 3D
// triangulation tests start from; and the same points moved, as the flip repair's tests move them.
#pragma once

#include <cmath>
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

// `p` with each point inside [-0.9, 0.9]^3 moved by up to `amount` in each coordinate; the
// others (the hull among them) stay.
inline std::vector<Vec3> moved_inner3(std::vector<Vec3> p, double amount, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-amount, amount);
  for (Vec3& q : p)
    if (std::fabs(q.x) < 0.9 && std::fabs(q.y) < 0.9 && std::fabs(q.z) < 0.9)
      q = q + Vec3{u(rng), u(rng), u(rng)};
  return p;
}

}  // namespace meshd::testing
