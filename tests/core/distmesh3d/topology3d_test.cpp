#include "core/distmesh3d/topology3d.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "tests/core/random_points3.h"

namespace meshd {
namespace {

using testing::random_points3;

TEST(Topology3d, KeepsTheTetrahedraInsideWithPositiveVolume) {
  Domain3 ball;
  ball.distance = [](Vec3 p) { return norm(p) - 0.8; };
  const std::vector<Vec3> points = random_points3(2000, 1);
  ThreadPool pool(2);
  const Topology3 t = triangulate3d(ball, points, 0, 0.01, 1e-9, &pool);
  ASSERT_GT(t.tets.size(), 1000u);
  for (const auto& v : t.tets) {
    const Vec3 a = points[v[0]], b = points[v[1]], c = points[v[2]], d = points[v[3]];
    EXPECT_GT(dot(b - a, cross(c - a, d - a)), 0.0);
    EXPECT_LT(norm(0.25 * (a + b + c + d)), 0.8 - 0.01);
  }
}

TEST(Topology3d, BarsAreTheUniqueEdgesAndEachNodeListsItsOwn) {
  const std::vector<Vec3> points = random_points3(500, 2);
  Domain3 box;
  box.distance = [](Vec3) { return -1.0; };
  const Topology3 t = triangulate3d(box, points, 0, 0.5, 1e-9, nullptr);
  std::set<std::array<int32_t, 2>> expected;
  for (const auto& v : t.tets)
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b) expected.insert({std::min(v[a], v[b]), std::max(v[a], v[b])});
  ASSERT_EQ(t.bars.size(), expected.size());
  EXPECT_TRUE(std::equal(t.bars.begin(), t.bars.end(), expected.begin()));

  ASSERT_EQ(t.bar_offsets.size(), points.size() + 1);
  ASSERT_EQ(t.bar_ends.size(), 2 * t.bars.size());
  for (size_t n = 0; n < points.size(); ++n) {
    int64_t previous = -1;
    for (int64_t k = t.bar_offsets[n]; k < t.bar_offsets[n + 1]; ++k) {
      const int64_t e = t.bar_ends[k];
      EXPECT_EQ(t.bars[e >> 1][e & 1], static_cast<int32_t>(n));
      EXPECT_GT(e >> 1, previous);  // in bar order
      previous = e >> 1;
    }
  }
}

TEST(Topology3d, AFreeNodeOnAnotherIsListed) {
  std::vector<Vec3> points = random_points3(300, 3);
  points.push_back(points[0] + Vec3{1e-7, 0.0, 0.0});  // on the fixed node 0
  points.push_back(points[5] + Vec3{0.0, 1e-7, 0.0});  // on the free node 5
  Domain3 box;
  box.distance = [](Vec3) { return -1.0; };
  const Topology3 t = triangulate3d(box, points, 1, 0.5, 1e-6, nullptr);
  EXPECT_EQ(t.coincident, (std::vector<int32_t>{300, 301}));
}

}  // namespace
}  // namespace meshd
