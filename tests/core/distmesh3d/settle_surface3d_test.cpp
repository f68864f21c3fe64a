#include "core/distmesh3d/settle_surface3d.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/mesh3d/tet_quality.cuh"

namespace meshd {
namespace {

// The half-space z < 0.
Domain3 below_the_plane() {
  Domain3 d;
  d.distance = [](Vec3 p) { return p.z; };
  d.bounds = {{-2, -2, -2}, {2, 2, 0}};
  return d;
}

double signed_volume(const std::vector<Vec3>& p, const std::array<int32_t, 4>& t) {
  return dot(p[t[1]] - p[t[0]], cross(p[t[2]] - p[t[0]], p[t[3]] - p[t[0]])) / 6.0;
}

// A pit: the tetrahedron a b c w with its cap a b c v taken out, v under the triangle a b c;
// w (fixed, first) stands for the interior below.
struct Pit {
  std::vector<Vec3> points{
      {0.5, 0.289, -0.8}, {0, 0, 0}, {1, 0, 0}, {0.5, 0.866, 0}, {0.5, 0.289, -0.3}};
  std::vector<std::array<int32_t, 4>> tets{{4, 1, 2, 0}, {4, 2, 3, 0}, {4, 3, 1, 0}};
  Pit() {
    for (auto& t : tets)
      if (signed_volume(points, t) < 0.0) std::swap(t[0], t[1]);
  }
};

TEST(SettleSurface3d, APitsNodeMovesOntoTheBoundary) {
  Pit pit;
  const SurfaceSettling s =
      settle_surface3d(below_the_plane(), 1e-8, pit.points, pit.tets, 1, nullptr);
  EXPECT_EQ(s.moved, 1);
  EXPECT_EQ(s.dropped, 0);
  EXPECT_EQ(s.stuck, 0);
  EXPECT_NEAR(pit.points[4].z, 0.0, 1e-12);
  EXPECT_NEAR(pit.points[4].x, 0.5, 1e-12);
  ASSERT_EQ(pit.tets.size(), 3u);
  // The three tetrahedra now fill a b c w.
  double total = 0.0;
  for (const auto& t : pit.tets) {
    EXPECT_GT(signed_volume(pit.points, t), 0.0);
    total += signed_volume(pit.points, t);
  }
  const std::array<int32_t, 4> whole{1, 2, 3, 0};
  EXPECT_NEAR(total, std::fabs(signed_volume(pit.points, whole)), 1e-12);
}

TEST(SettleSurface3d, AFixedNodeStays) {
  Pit pit;
  const SurfaceSettling s =
      settle_surface3d(below_the_plane(), 1e-8, pit.points, pit.tets, 5, nullptr);
  EXPECT_EQ(s.moved, 0);
  EXPECT_EQ(pit.points[4].z, -0.3);
}

TEST(SettleSurface3d, ACapFlattenedByTheMoveGoes) {
  // One tetrahedron, three nodes on the plane and the fourth under them: moved onto the plane,
  // it would be flat.
  std::vector<Vec3> points{{0, 0, 0}, {1, 0, 0}, {0.5, 0.866, 0}, {0.5, 0.289, -0.2}};
  std::vector<std::array<int32_t, 4>> tets{{0, 1, 2, 3}};
  if (signed_volume(points, tets[0]) < 0.0) std::swap(tets[0][0], tets[0][1]);
  const SurfaceSettling s = settle_surface3d(below_the_plane(), 1e-8, points, tets, 0, nullptr);
  EXPECT_EQ(s.moved, 1);
  EXPECT_EQ(s.dropped, 1);
  EXPECT_TRUE(tets.empty());
}

}  // namespace
}  // namespace meshd
