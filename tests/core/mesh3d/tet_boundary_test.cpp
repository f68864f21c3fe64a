#include "core/mesh3d/tet_boundary.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>

#include "core/common/vec3.h"
#include "tests/core/mesh3d/structured_tet_mesh.h"

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

TEST(TetBoundary, TheStructuredCubeHasTwoTrianglesPerSquareOfEachSide) {
  const int n = 3;
  const TetMesh mesh = testing::structured_cube_mesh(n);
  ASSERT_EQ(mesh.boundary_faces.size(), 6u * 2 * n * n);
  std::map<int32_t, int> per_group;
  for (size_t i = 0; i < mesh.boundary_faces.size(); ++i) {
    const auto& f = mesh.boundary_faces[i];
    ++per_group[mesh.boundary_tags[i]];
    // Outward: the normal points the way of the side's axis (x0 to -x, x1 to +x, ...).
    const Vec3 a = mesh.points[f[0]];
    const Vec3 normal = cross(mesh.points[f[1]] - a, mesh.points[f[2]] - a);
    const double along[3] = {normal.x, normal.y, normal.z};
    const int g = mesh.boundary_tags[i];
    EXPECT_GT(g % 2 == 0 ? -along[g / 2] : along[g / 2], 0.0) << "face " << i;
  }
  for (int g = 0; g < 6; ++g) EXPECT_EQ(per_group[g], 2 * n * n) << mesh.boundary_names[g];
}

TEST(TetBoundary, AFaceSharedByThreeIsNotBoundary) {
  // Three tetrahedra on the face (0, 1, 2), however turned: it is used thrice, so not once.
  const std::vector<std::array<int32_t, 4>> tets{{0, 1, 2, 3}, {0, 2, 1, 4}, {0, 1, 2, 5}};
  for (const auto& f : tet_boundary_faces(tets)) {
    auto key = f;
    std::sort(key.begin(), key.end());
    EXPECT_NE(key, (std::array<int32_t, 3>{0, 1, 2}));
  }
  EXPECT_EQ(tet_boundary_faces(tets).size(), 9u);
}

}  // namespace
}  // namespace meshd
