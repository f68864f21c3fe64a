#include "core/mesh3d/tet_boundary.h"

#include <gtest/gtest.h>

#include <map>

#include "core/common/vec3.h"

namespace meshd {
namespace {

// The unit cube in six tetrahedra around its diagonal 0-7 (vertex i at (i&1, i>>1&1, i>>2&1)),
// each turned positive.
struct Cube {
  std::vector<Vec3> points;
  std::vector<std::array<int32_t, 4>> tets;
};

Cube cube() {
  Cube c;
  for (int i = 0; i < 8; ++i)
    c.points.push_back({static_cast<double>(i & 1), static_cast<double>((i >> 1) & 1),
                        static_cast<double>((i >> 2) & 1)});
  const int paths[6][2] = {{1, 3}, {2, 3}, {1, 5}, {4, 5}, {2, 6}, {4, 6}};
  for (const auto& p : paths) {
    std::array<int32_t, 4> t{0, p[0], p[1], 7};
    const Vec3 a = c.points[t[0]];
    if (dot(c.points[t[1]] - a, cross(c.points[t[2]] - a, c.points[t[3]] - a)) < 0.0)
      std::swap(t[1], t[2]);
    c.tets.push_back(t);
  }
  return c;
}

TEST(TetBoundary, TheCubesTwelveTrianglesPointOut) {
  const Cube c = cube();
  const auto faces = tet_boundary_faces(c.tets);
  ASSERT_EQ(faces.size(), 12u);
  const Vec3 centre{0.5, 0.5, 0.5};
  std::map<std::array<int32_t, 3>, int> seen;
  for (const auto& f : faces) {
    const Vec3 a = c.points[f[0]], b = c.points[f[1]], d = c.points[f[2]];
    const Vec3 normal = cross(b - a, d - a);
    EXPECT_GT(dot(normal, a - centre), 0.0);  // counter-clockwise seen from outside
    auto key = f;
    std::sort(key.begin(), key.end());
    EXPECT_EQ(++seen[key], 1);
  }
}

TEST(TetBoundary, OneTetrahedronIsAllBoundaryAndTheFacesFollowTheOrder) {
  const std::vector<std::array<int32_t, 4>> one{{0, 1, 2, 3}};
  const auto faces = tet_boundary_faces(one);
  ASSERT_EQ(faces.size(), 4u);
  for (int k = 0; k < 4; ++k) EXPECT_EQ(faces[k], tet_face(one[0], k));
}

}  // namespace
}  // namespace meshd
