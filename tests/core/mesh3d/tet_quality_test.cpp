#include "core/mesh3d/tet_quality.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "tests/core/mesh3d/structured_tet_mesh.h"

namespace meshd {
namespace {

// The regular tetrahedron of edge 2 sqrt 2, positively oriented.
const Vec3 kA{1, 1, 1}, kB{-1, 1, -1}, kC{1, -1, -1}, kD{-1, -1, 1};

TEST(TetQuality, TheRegularTetrahedronIsOne) {
  ASSERT_GT(dot(kB - kA, cross(kC - kA, kD - kA)), 0.0);
  EXPECT_NEAR(oriented_tet_radius_ratio(kA, kB, kC, kD), 1.0, 1e-12);
  double lo = 0.0, hi = 0.0;
  tet_dihedral_range(kA, kB, kC, kD, lo, hi);
  const double regular = std::acos(1.0 / 3.0) * 180.0 / M_PI;
  EXPECT_NEAR(regular, 70.5288, 1e-4);
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

TEST(TetQuality, SixDihedralAnglesInEdgeOrder) {
  // The corner tetrahedron 0, e1, e2, e3: right angles at the three edges from the origin, and
  // acos(1 / sqrt 3) = 54.74 degrees where the slanted face meets the others.
  const Vec3 o{0, 0, 0}, x{1, 0, 0}, y{0, 1, 0}, z{0, 0, 1};
  double angles[6];
  tet_dihedral_angles(o, x, y, z, angles);
  const double slanted = std::acos(1.0 / std::sqrt(3.0)) * 180.0 / M_PI;
  const double expected[6] = {90, 90, 90, slanted, slanted, slanted};  // ab ac ad bc bd cd
  for (int e = 0; e < 6; ++e) EXPECT_NEAR(angles[e], expected[e], 1e-9) << "edge " << e;
  // Turned over: the same angles.
  tet_dihedral_angles(x, o, y, z, angles);
  const double swapped[6] = {90, slanted, slanted, 90, 90, slanted};  // xo xy xz oy oz yz
  for (int e = 0; e < 6; ++e) EXPECT_NEAR(angles[e], swapped[e], 1e-9) << "edge " << e;
}

TEST(TetQuality, KuhnsTetrahedron) {
  // The cube's corner path 0, e1, e1 + e2, e1 + e2 + e3, which the structured cube mesh is made
  // of: r_in = (sqrt 2 - 1) / 2, R_circ = sqrt 3 / 2, dihedral angles 45, 60 and 90 degrees.
  const Vec3 a{0, 0, 0}, b{1, 0, 0}, c{1, 1, 0}, d{1, 1, 1};
  EXPECT_NEAR(oriented_tet_radius_ratio(a, b, c, d), std::sqrt(3.0) * (std::sqrt(2.0) - 1.0),
              1e-12);
  double angles[6];
  tet_dihedral_angles(a, b, c, d, angles);
  const double expected[6] = {45, 90, 60, 90, 90, 45};
  for (int e = 0; e < 6; ++e) EXPECT_NEAR(angles[e], expected[e], 1e-9) << "edge " << e;
}

TEST(TetQuality, NearlyFlatIsNearlyZeroWithoutNaN) {
  // The sliver of a unit square's corners, two of them lifted by e, has q = 3 e / sqrt 2 to
  // first order, down to the last digits.
  for (const double e : {1e-3, 1e-8, 1e-15}) {
    const Vec3 a{0, 0, 0}, b{1, 1, 0}, c{0, 1, e}, d{1, 0, e};
    const double q = oriented_tet_radius_ratio(a, b, c, d);
    EXPECT_NEAR(q, 3.0 / std::sqrt(2.0) * e, 1e-3 * e) << e;
  }
  // Three corners on a line: one face of zero area, so the smallest angle is 0.
  double lo = 1.0, hi = 1.0;
  tet_dihedral_range({0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 1}, lo, hi);
  EXPECT_EQ(lo, 0.0);
  EXPECT_EQ(oriented_tet_radius_ratio({0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 1}), 0.0);
}

TEST(TetQuality, TheLengthUnitDoesNotMatter) {
  // Lengths whose squares and fourth powers would underflow or overflow a double.
  for (const double s : {1e-100, 1e100}) {
    EXPECT_NEAR(oriented_tet_radius_ratio(s * kA, s * kB, s * kC, s * kD), 1.0, 1e-12) << s;
    double lo = 0.0, hi = 0.0;
    tet_dihedral_range(s * kA, s * kB, s * kC, s * kD, lo, hi);
    EXPECT_NEAR(lo, std::acos(1.0 / 3.0) * 180.0 / M_PI, 1e-9) << s;
  }
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(oriented_tet_radius_ratio(kA, kB, kC, {inf, 0, 0}), 0.0);
  EXPECT_EQ(oriented_tet_radius_ratio(kA, kB, kC, {std::nan(""), 0, 0}), 0.0);
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

TEST(TetQuality, TheStructuredCubeIsAllKuhnTetrahedra) {
  const TetMesh mesh = testing::structured_cube_mesh(3);
  const TetQualityStats s = summarize_tet_quality(mesh);
  const double kuhn = std::sqrt(3.0) * (std::sqrt(2.0) - 1.0);  // 0.717
  EXPECT_NEAR(s.q_min, kuhn, 1e-12);
  EXPECT_NEAR(s.q_mean, kuhn, 1e-12);
  EXPECT_EQ(s.histogram[7], 162);
  EXPECT_NEAR(s.min_dihedral_deg, 45.0, 1e-9);
  EXPECT_NEAR(s.max_dihedral_deg, 90.0, 1e-9);
  EXPECT_NEAR(s.volume, 1.0, 1e-12);
  const std::vector<double> q = tet_quality(mesh);
  ASSERT_EQ(q.size(), 162u);
  EXPECT_NEAR(q[100], kuhn, 1e-12);
}

TEST(TetQuality, AnEmptyMeshSummarisesToZeros) {
  const TetQualityStats s = summarize_tet_quality(TetMesh{});
  EXPECT_EQ(s.q_min, 0.0);
  EXPECT_EQ(s.volume, 0.0);
  EXPECT_EQ(s.histogram[0], 0);
}

TEST(TetQuality, ATurnedOverTetrahedronLandsInTheFirstBin) {
  const std::vector<Vec3> points{kA, kB, kC, kD};
  const TetQualityStats s = summarize_tet_quality(points, {{1, 0, 2, 3}});
  EXPECT_NEAR(s.q_min, -1.0, 1e-12);
  EXPECT_EQ(s.histogram[0], 1);
  EXPECT_LT(s.volume, 0.0);
}

}  // namespace
}  // namespace meshd
