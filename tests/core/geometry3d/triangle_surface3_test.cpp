#include "core/geometry3d/triangle_surface3.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <variant>

#include "core/common/error.h"
#include "core/common/vec2.h"
#include "core/geometry3d/compile3d.h"
#include "core/geometry3d/sdf3_eval.cuh"
#include "core/geometry3d/sharp_features3.h"
#include "core/geometry3d/surface_sdf3.cuh"
#include "tests/core/geometry3d/shape3d_builders.h"

namespace meshd {
namespace {

using testing::cube_polyhedron;
using testing::cuboid;

double distance(const Shape3& shape, Vec3 p) {
  const Program3 program = compile_geometry3(shape);
  return eval_sdf3(program.view(), p);
}

std::vector<Vec3> random_points(int n, double half, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-half, half);
  std::vector<Vec3> out;
  for (int i = 0; i < n; ++i) out.push_back({u(rng), u(rng), u(rng)});
  return out;
}

// A UV sphere of radius r: `rings` latitude bands of `segments` quads, poles as fans.
Polyhedron uv_sphere(double r, int rings, int segments) {
  Polyhedron p;
  p.vertices.push_back({0, 0, r});
  for (int i = 1; i < rings; ++i) {
    const double theta = M_PI * i / rings;
    for (int j = 0; j < segments; ++j) {
      const double phi = 2 * M_PI * j / segments;
      p.vertices.push_back({r * std::sin(theta) * std::cos(phi),
                            r * std::sin(theta) * std::sin(phi), r * std::cos(theta)});
    }
  }
  p.vertices.push_back({0, 0, -r});
  const int south = static_cast<int>(p.vertices.size()) - 1;
  const auto ring = [&](int i, int j) { return 1 + (i - 1) * segments + (j % segments); };
  for (int j = 0; j < segments; ++j) p.triangles.push_back({0, ring(1, j), ring(1, j + 1)});
  for (int i = 1; i + 1 < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      p.triangles.push_back({ring(i, j), ring(i + 1, j), ring(i + 1, j + 1)});
      p.triangles.push_back({ring(i, j), ring(i + 1, j + 1), ring(i, j + 1)});
    }
  for (int j = 0; j < segments; ++j)
    p.triangles.push_back({south, ring(rings - 1, j + 1), ring(rings - 1, j)});
  return p;
}

TEST(TriangleSurface3, ACubeOfTrianglesIsTheCuboidsDistance) {
  const Shape3 box = cuboid({-1, -1, -1}, {1, 1, 1});
  for (bool inward : {false, true}) {
    const Shape3 poly = cube_polyhedron(-1, 1, inward);
    for (Vec3 p : random_points(2000, 2.5, 7))
      EXPECT_NEAR(distance(poly, p), distance(box, p), 1e-12) << p.x << " " << p.y << " " << p.z;
  }
}

TEST(TriangleSurface3, TheTreeFindsTheNearestTriangleAsVisitingAllDoes) {
  const Polyhedron sphere = uv_sphere(1.0, 40, 80);
  const TriangleSurface3 s = build_triangle_surface3(sphere.vertices, sphere.triangles, "poly");
  EXPECT_EQ(s.sharp_edges.size(), 0u);  // 4.5-degree facets: smooth
  for (Vec3 p : random_points(500, 1.6, 11)) {
    double brute = INFINITY;
    for (const auto& t : sphere.triangles) {
      const auto n = surface_detail::nearest_on_triangle(
          p, sphere.vertices[t[0]], sphere.vertices[t[1]], sphere.vertices[t[2]]);
      brute = std::min(brute, norm(p - n.point));
    }
    const double d = sdf3_surface(s.view(), p);
    EXPECT_NEAR(std::fabs(d), brute, 1e-12);
    // Facets lie within 1 - cos(2.25 degrees) of the sphere.
    if (norm(p) < 0.99) {
      EXPECT_LT(d, 0.0);
    } else if (norm(p) > 1.0) {
      EXPECT_GT(d, 0.0);
    }
  }
}

TEST(TriangleSurface3, ACapKeepsTheDistanceNearTheSurfaceAndTheSignBeyond) {
  // An L-shaped prism, not convex, so that a ray from inside may cross it three times.
  Polyhedron l;
  const Vec2 outline[6] = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
  for (double z : {0.0, 1.0})
    for (Vec2 q : outline) l.vertices.push_back({q.x, q.y, z});
  // The bottom (fan from 0, seen from below) and the top, and two triangles per side.
  for (int k = 1; k + 1 < 6; ++k) {
    l.triangles.push_back({0, k + 1, k});
    l.triangles.push_back({6, 6 + k, 6 + k + 1});
  }
  for (int k = 0; k < 6; ++k) {
    const int a = k, b = (k + 1) % 6;
    l.triangles.push_back({a, b, 6 + b});
    l.triangles.push_back({a, 6 + b, 6 + a});
  }
  const TriangleSurface3 s = build_triangle_surface3(l.vertices, l.triangles, "poly");
  for (Vec3 p : random_points(3000, 3.0, 5)) {
    const double exact = sdf3_surface(s.view(), p);
    const double capped = sdf3_surface(s.view(), p, 0.2);
    if (std::fabs(exact) < 0.2) {
      EXPECT_EQ(capped, exact);
    } else {
      EXPECT_EQ(capped, exact < 0 ? -0.2 : 0.2) << p.x << " " << p.y << " " << p.z;
    }
  }
  // The program passes its cap down: the cube of triangles deep inside.
  const Program3 cube = compile_geometry3(cube_polyhedron(-1, 1));
  EXPECT_EQ(eval_sdf3(cube.view(), {0.1, 0.2, 0.3}, nullptr, 0.25), -0.25);
  EXPECT_DOUBLE_EQ(eval_sdf3(cube.view(), {0.1, 0.2, 0.9}, nullptr, 0.25), -0.1);
}

TEST(TriangleSurface3, TransformsMoveTheSurface) {
  Similarity3 t;
  t.scale = 2.0;
  t.axis = {1, 1, 0};
  t.angle = 0.7;
  t.offset = {0.5, -1, 3};
  const Shape3 poly = testing::transformed3(cube_polyhedron(-1, 1), t);
  const Shape3 box = testing::transformed3(cuboid({-1, -1, -1}, {1, 1, 1}), t);
  for (Vec3 p : random_points(500, 5, 3)) EXPECT_NEAR(distance(poly, p), distance(box, p), 1e-11);
}

TEST(TriangleSurface3, ACubesSharpEdgesAreTheCuboids) {
  const Program3 poly = compile_geometry3(cube_polyhedron(-1, 1));
  const Program3 box = compile_geometry3(cuboid({-1, -1, -1}, {1, 1, 1}));
  EXPECT_EQ(poly.surfaces.front()->sharp_edges.size(), 12u);  // not the faces' diagonals
  for (double spacing : {0.3, 0.5, 2.0}) {
    auto a = sharp_features3(poly, spacing), b = sharp_features3(box, spacing);
    const auto less = [](Vec3 u, Vec3 v) {
      return u.x < v.x || (u.x == v.x && (u.y < v.y || (u.y == v.y && u.z < v.z)));
    };
    ASSERT_EQ(a.size(), b.size()) << spacing;
    std::sort(a.begin(), a.end(), less);
    std::sort(b.begin(), b.end(), less);
    for (size_t i = 0; i < a.size(); ++i) EXPECT_LT(norm(a[i] - b[i]), 1e-12);
  }
}

// The error's field and a fragment of its message.
void expect_refused(Polyhedron p, const std::string& field, const std::string& says) {
  try {
    build_triangle_surface3(p.vertices, p.triangles, "volume.geometry.polyhedron");
    FAIL() << "accepted; expected: " << says;
  } catch (const Error& e) {
    EXPECT_EQ(e.field(), field);
    EXPECT_NE(std::string(e.what()).find(says), std::string::npos) << e.what();
  }
}

TEST(TriangleSurface3, BadSurfacesAreNamed) {
  const auto cube = std::get<Polyhedron>(cube_polyhedron(-1, 1).node);
  const std::string f = "volume.geometry.polyhedron.triangles";
  Polyhedron open = cube;
  open.triangles.pop_back();
  expect_refused(open, f, "closed");
  Polyhedron twisted = cube;
  std::swap(twisted.triangles[0][1], twisted.triangles[0][2]);
  expect_refused(twisted, f, "same direction");
  Polyhedron flat = cube;
  flat.triangles[0] = {0, 0, 3};
  expect_refused(flat, f, "zero area");
  Polyhedron few = cube;
  few.triangles.resize(3);
  expect_refused(few, f, "at least 4");
  Polyhedron outside = cube;
  outside.triangles[5][2] = 8;
  expect_refused(outside, f, "outside [0, 8)");
}

// The cube [lo, hi]^3 added to `p`, its corner k the vertex `shared[k]` where that is not -1.
void add_cube(Polyhedron& p, double lo, double hi,
              std::array<int32_t, 8> shared = {-1, -1, -1, -1, -1, -1, -1, -1}) {
  const auto cube = std::get<Polyhedron>(cube_polyhedron(lo, hi).node);
  std::array<int32_t, 8> index{};
  for (int k = 0; k < 8; ++k) {
    index[k] = shared[k];
    if (index[k] >= 0) continue;
    index[k] = static_cast<int32_t>(p.vertices.size());
    p.vertices.push_back(cube.vertices[k]);
  }
  for (const auto& t : cube.triangles)
    p.triangles.push_back({index[t[0]], index[t[1]], index[t[2]]});
}

TEST(TriangleSurface3, SurfacesThatCrossThemselvesAreRefused) {
  const std::string f = "volume.geometry.polyhedron.triangles";
  // Two closed cubes in one surface: apart they are a solid of two parts; overlapping, the
  // sheets cross and the overlap is inside twice.
  Polyhedron apart;
  add_cube(apart, -1, 1);
  add_cube(apart, 2, 3);
  EXPECT_NO_THROW(build_triangle_surface3(apart.vertices, apart.triangles, "p"));
  Polyhedron overlapping;
  add_cube(overlapping, -1, 1);
  add_cube(overlapping, 0, 2);
  expect_refused(overlapping, f, "intersects itself");
  // The second cube's corner 0 is the first's corner 7: the surface touches itself there.
  Polyhedron touching;
  add_cube(touching, -1, 1);
  add_cube(touching, 1, 3, {7, -1, -1, -1, -1, -1, -1, -1});
  expect_refused(touching, f, "intersects itself");
  // A top corner of a cube pulled down through the bottom face: its triangles pierce it.
  Polyhedron pierced = std::get<Polyhedron>(cube_polyhedron(-1, 1).node);
  pierced.vertices[7] = {0.2, 0.3, -3};
  expect_refused(pierced, f, "cross");
}

// A fine sphere (some 40k triangles, as a scanned part has) passes the check whole.
TEST(TriangleSurface3, AFineSphereDoesNotCrossItself) {
  const Polyhedron sphere = uv_sphere(1.0, 100, 200);
  const TriangleSurface3 s = build_triangle_surface3(sphere.vertices, sphere.triangles, "p");
  EXPECT_EQ(s.triangles.size(), 3 * sphere.triangles.size());
}

}  // namespace
}  // namespace meshd
