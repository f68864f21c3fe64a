#include "core/distmesh3d/initial_points3d.h"

#include <gtest/gtest.h>

#include <cmath>

namespace meshd {
namespace {

Domain3 unit_ball() {
  Domain3 d;
  d.distance = [](Vec3 p) { return norm(p) - 1.0; };
  d.bounds = {{-1, -1, -1}, {1, 1, 1}};
  return d;
}

TEST(InitialPoints3d, FillTheBallAtTheDensityOfRegularTetrahedra) {
  const double h0 = 0.1;
  const std::vector<Vec3> points = initial_points3d(unit_ball(), h0, 0.1, 1);
  // Each node owns sqrt(2) h0^3 / 2 of volume (bcc_cube_side): the ball, plus the geps shell.
  const double expected =
      (4.0 / 3.0) * M_PI * std::pow(1.0 + 0.1 * h0, 3) / (std::sqrt(2.0) * h0 * h0 * h0 / 2.0);
  EXPECT_NEAR(static_cast<double>(points.size()), expected, 0.03 * expected);
  for (const Vec3& p : points) EXPECT_LT(norm(p) - 1.0, 0.1 * h0);
}

TEST(InitialPoints3d, FixedNodesComeFirstAndKeepLatticePointsAway) {
  Domain3 d = unit_ball();
  d.fixed = {{0.0, 0.0, 1.0}, {0.0, 0.0, -1.0}, {0.01, 0.02, 0.03}};
  const double h0 = 0.1;
  const std::vector<Vec3> points = initial_points3d(d, h0, 0.1, 1);
  ASSERT_GT(points.size(), 3u);
  for (size_t i = 0; i < d.fixed.size(); ++i) EXPECT_TRUE(points[i] == d.fixed[i]);
  for (size_t i = d.fixed.size(); i < points.size(); ++i)
    for (const Vec3& f : d.fixed) EXPECT_GE(norm(points[i] - f), 0.5 * h0);
}

TEST(InitialPoints3d, ThinToTheCubeOfTheSizeRatio) {
  Domain3 d;
  d.distance = [](Vec3 p) {
    const double q = std::max({std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)});
    return q - 1.0;
  };
  d.bounds = {{-1, -1, -1}, {1, 1, 1}};
  d.size = [](Vec3 p) { return p.x < 0.0 ? 1.0 : 2.0; };
  const std::vector<Vec3> points = initial_points3d(d, 0.1, 0.1, 7);
  int64_t fine = 0, coarse = 0;
  for (const Vec3& p : points) (p.x < 0.0 ? fine : coarse) += 1;
  // Half the edge length: an eighth of the nodes (the dither follows the ratio closely).
  EXPECT_NEAR(static_cast<double>(coarse) / static_cast<double>(fine), 0.125, 0.01);
}

TEST(InitialPoints3d, TheSameSeedGivesTheSameNodes) {
  Domain3 d = unit_ball();
  d.size = [](Vec3 p) { return 1.0 + norm(p); };
  const auto a = initial_points3d(d, 0.1, 0.1, 3), b = initial_points3d(d, 0.1, 0.1, 3),
             c = initial_points3d(d, 0.1, 0.1, 4);
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) EXPECT_TRUE(a[i] == b[i]);
  bool differ = a.size() != c.size();
  for (size_t i = 0; !differ && i < a.size(); ++i) differ = !(a[i] == c[i]);
  EXPECT_TRUE(differ);
}

}  // namespace
}  // namespace meshd
