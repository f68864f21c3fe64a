// The filtered orientation and in-sphere tests (filtered_predicates3.cuh) against CGAL's exact
// ones: never a wrong sign, undecided only near degeneracy, and decided on points in general
// position.
#include "core/delaunay/filtered_predicates3.cuh"

#include <gtest/gtest.h>

#include <array>
#include <random>
#include <utility>
#include <vector>

#include "core/delaunay/exact_predicates.h"
#include "tests/core/random_points3.h"

namespace meshd {
namespace {

using testing::random_points3;

// Five points: random ones, the first four turned positive.
std::array<Vec3, 5> positive_five(const std::vector<Vec3>& p, size_t i) {
  std::array<Vec3, 5> q{p[i], p[i + 1], p[i + 2], p[i + 3], p[i + 4]};
  if (orientation3_sign(q[0], q[1], q[2], q[3]) < 0) std::swap(q[0], q[1]);
  return q;
}

TEST(FilteredPredicates3, DecideRandomPointsAsTheExactOnesDo) {
  const std::vector<Vec3> p = random_points3(5000, 7);
  for (size_t i = 0; i + 5 <= p.size(); i += 5) {
    const auto q = positive_five(p, i);
    EXPECT_EQ(orientation3_filtered(q[0], q[1], q[2], q[3]), 1);
    EXPECT_EQ(orientation3_filtered(q[1], q[0], q[2], q[3]), -1);
    const int exact = in_sphere_sign(q[0], q[1], q[2], q[3], q[4]);
    ASSERT_NE(exact, 0);
    EXPECT_EQ(in_sphere_filtered(q[0], q[1], q[2], q[3], q[4]), exact);
  }
}

// Points of a unit lattice are coplanar and cospherical by the thousand; nudged by a few ulps,
// they sit where the filter must either answer right or not at all.
TEST(FilteredPredicates3, NeverContradictTheExactOnesNearDegeneracy) {
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> cell(0, 2);
  std::uniform_int_distribution<int> nudge(-2, 2);
  const auto point = [&] {
    Vec3 v{1.0 * cell(rng), 1.0 * cell(rng), 1.0 * cell(rng)};
    const int k = nudge(rng);
    if (k != 0) v.x = v.x + k * 1e-16 * (1.0 + v.x);
    return v;
  };
  int decided = 0, undecided = 0;
  for (int i = 0; i < 20000; ++i) {
    const Vec3 a = point(), b = point(), c = point(), d = point(), e = point();
    const int orient = orientation3_sign(a, b, c, d);
    const int filtered = orientation3_filtered(a, b, c, d);
    if (filtered != 0) {
      EXPECT_EQ(filtered, orient);
    }
    if (orient == 0) {
      EXPECT_EQ(filtered, 0);
      continue;
    }
    const bool positive = orient > 0;
    const int exact = positive ? in_sphere_sign(a, b, c, d, e) : in_sphere_sign(b, a, c, d, e);
    const int sphere =
        positive ? in_sphere_filtered(a, b, c, d, e) : in_sphere_filtered(b, a, c, d, e);
    if (sphere != 0) {
      EXPECT_EQ(sphere, exact);
      ++decided;
    } else {
      ++undecided;
    }
    if (exact == 0) {
      EXPECT_EQ(sphere, 0);
    }
  }
  // Both kinds occur, so that the test holds the filter to both answers.
  EXPECT_GT(decided, 100);
  EXPECT_GT(undecided, 100);
}

}  // namespace
}  // namespace meshd
