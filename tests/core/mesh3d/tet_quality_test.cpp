#include "core/mesh3d/tet_quality.h"

#include <gtest/gtest.h>

#include <cmath>

namespace meshd {
namespace {

// The regular tetrahedron of edge 2 sqrt 2, positively oriented.
const Vec3 kA{1, 1, 1}, kB{-1, 1, -1}, kC{1, -1, -1}, kD{-1, -1, 1};

TEST(TetQuality, TheRegularTetrahedronIsOne) {
  ASSERT_GT(dot(kB - kA, cross(kC - kA, kD - kA)), 0.0);
  EXPECT_NEAR(oriented_tet_radius_ratio(kA, kB, kC, kD), 1.0, 1e-12);
  double lo = 0.0, hi = 0.0;
  tet_dihedral_range(kA, kB, kC, kD, lo, hi);
  const double regular = std::acos(1.0 / 3.0) * 180.0 / M_PI;  // 70.53 degrees
  EXPECT_NEAR(lo, regular, 1e-9);
  EXPECT_NEAR(hi, regular, 1e-9);
}

TEST(TetQuality, ASimilarTetrahedronHasTheSameQuality) {
  const auto f = [](Vec3 p) { return Vec3{3.0 * p.y + 5.0, -3.0 * p.x, 3.0 * p.z - 1.0}; };
  EXPECT_NEAR(oriented_tet_radius_ratio(f(kA), f(kB), f(kC), f(kD)), 1.0, 1e-12);
}

TEST(TetQuality, TurnedOverIsNegativeAndFlatIsZero) {
  EXPECT_NEAR(oriented_tet_radius_ratio(kB, kA, kC, kD), -1.0, 1e-12);
  EXPECT_EQ(oriented_tet_radius_ratio({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}), 0.0);
  EXPECT_EQ(oriented_tet_radius_ratio({0, 0, 0}, {0, 0, 0}, {0, 1, 0}, {0, 0, 1}), 0.0);
}

TEST(TetQuality, ASliverHasLowQualityAndExtremeDihedrals) {
  // Four points of a square, two lifted a little: the classic sliver.
  const double e = 0.05;
  const Vec3 a{0, 0, 0}, b{1, 1, 0}, c{1, 0, e}, d{0, 1, e};
  const double q = std::fabs(oriented_tet_radius_ratio(a, b, c, d));
  EXPECT_LT(q, 0.2);
  double lo = 0.0, hi = 0.0;
  tet_dihedral_range(a, b, c, d, lo, hi);
  EXPECT_LT(lo, 10.0);
  EXPECT_GT(hi, 170.0);
}

TEST(TetQuality, TheRightCornerOfTheUnitCube) {
  // The corner tetrahedron 0, e1, e2, e3: q = 3 r_in / R = 3 (1 / (3 + sqrt 3)) / (sqrt 3 / 2).
  const double expected = 3.0 * (1.0 / (3.0 + std::sqrt(3.0))) / (std::sqrt(3.0) / 2.0);
  EXPECT_NEAR(oriented_tet_radius_ratio({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}), expected,
              1e-12);
  double lo = 0.0, hi = 0.0;
  tet_dihedral_range({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, lo, hi);
  EXPECT_NEAR(lo, std::acos(1.0 / std::sqrt(3.0)) * 180.0 / M_PI,
              1e-9);  // 54.7 at the slanted face
  EXPECT_NEAR(hi, 90.0, 1e-9);
}

TEST(TetQuality, TheSummaryCountsVolumeAndBins) {
  const std::vector<Vec3> points{kA, kB, kC, kD, {0, 0, 0}};
  // The regular tetrahedron cut at its centre into four: each q < 1, the volume unchanged.
  const std::vector<std::array<int32_t, 4>> tets{
      {4, 1, 2, 3}, {0, 4, 2, 3}, {0, 1, 4, 3}, {0, 1, 2, 4}};
  const TetQualityStats s = summarize_tet_quality(points, tets);
  EXPECT_NEAR(s.volume, std::pow(2.0 * std::sqrt(2.0), 3) / (6.0 * std::sqrt(2.0)), 1e-12);
  EXPECT_GT(s.q_min, 0.0);
  EXPECT_LT(s.q_min, 1.0);
  int64_t total = 0;
  for (int64_t n : s.histogram) total += n;
  EXPECT_EQ(total, 4);
  EXPECT_GE(s.min_dihedral_deg, 0.0);
  EXPECT_LE(s.max_dihedral_deg, 180.0);
}

}  // namespace
}  // namespace meshd
