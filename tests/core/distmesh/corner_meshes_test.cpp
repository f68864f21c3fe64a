// Whole meshes of CSG shapes whose corners come from two primitives' boundaries crossing (a tooth
// meeting a disk, a slot cut into one, two disks, an ellipse and a circle, a disk cut by a line):
// every corner is a node, bitwise, no node lies outside, boundary nodes lie on the boundary, and
// the worst element stays good.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "core/common/thread_pool.h"
#include "core/distmesh/compiled_problem.h"
#include "core/distmesh/cpu_engine.h"
#include "core/distmesh/distmesh.h"
#include "core/geometry/sdf_eval.cuh"
#include "core/mesh/validity.h"
#include "tests/core/geometry/shape_builders.h"

namespace meshd {
namespace {

using testing::circle;
using testing::csg;
using testing::ellipse;
using testing::half_plane;
using testing::rectangle;
using testing::transformed;

constexpr double kPi = std::numbers::pi;

struct CornerCase {
  std::string name;
  Shape shape;
  double h0;
  size_t corners;  // expected fixed points from auto_corners
};

Shape gear(int teeth) {
  std::vector<Shape> rim = {circle({0, 0}, 1)};
  for (int k = 0; k < teeth; ++k)
    rim.push_back(
        transformed(rectangle({0.95, -0.1}, {1.25, 0.1}), 1, 2 * kPi * k / teeth, {0, 0}));
  return csg(CsgOp::kDifference,
             {csg(CsgOp::kUnion, rim),
              csg(CsgOp::kUnion, {circle({0, 0}, 0.3), rectangle({0.2, -0.08}, {0.42, 0.08})})});
}

std::vector<CornerCase> cases() {
  return {
      {"gear: tooth roots (line-circle, concave), keyway (line-circle, convex)", gear(8), 0.04,
       8 * 4 + 4},
      {"disk minus a slot (line-circle, concave)",
       csg(CsgOp::kDifference, {circle({0, 0}, 1), rectangle({0.5, -0.15}, {2, 0.15})}), 0.04, 4},
      {"two disks (circle-circle, concave)",
       csg(CsgOp::kUnion, {circle({0, 0}, 1), circle({1.2, 0}, 0.8)}), 0.05, 2},
      {"crescent (circle-circle, convex)",
       csg(CsgOp::kDifference, {circle({0, 0}, 1), circle({0.9, 0}, 0.7)}), 0.04, 2},
      {"ellipse minus a disk (ellipse-circle)",
       csg(CsgOp::kDifference, {ellipse({0, 0}, 2, 1), circle({2, 0}, 0.6)}), 0.06, 2},
      {"ellipses crossed (ellipse-ellipse)",
       csg(CsgOp::kUnion,
           {ellipse({0, 0}, 1.5, 0.6), transformed(ellipse({0, 0}, 1.5, 0.6), 1, kPi / 2, {0, 0})}),
       0.05, 4},
      {"disk cut by a line (line-circle, convex)",
       csg(CsgOp::kIntersection, {circle({0, 0}, 1), half_plane({1, 1}, 0.6)}), 0.04, 2},
  };
}

TEST(CornerMeshes, EveryCrossingIsANodeAndTheBoundaryIsKept) {
  ThreadPool pool(2);
  for (const CornerCase& k : cases()) {
    SCOPED_TRACE(k.name);
    Problem p;
    p.geometry = k.shape;
    p.h0 = k.h0;
    const CompiledProblem c = compile_problem(p);
    ASSERT_EQ(c.fixed_points.size(), k.corners);
    CpuEngine engine(pool);
    const MeshResult r = generate_mesh(c, engine, nullptr, nullptr);
    const Mesh& m = r.mesh;
    const double h0 = c.h0;
    std::printf("[ measured ] %s: nodes %zu, corners %zu, q_min %.3f, q_mean %.4f, iterations %d\n",
                k.name.c_str(), m.points.size(), c.fixed_points.size(), r.quality.q_min,
                r.quality.q_mean, r.stats.iterations);
    EXPECT_TRUE(check_validity(m).valid());
    for (Vec2 f : c.fixed_points) {
      EXPECT_TRUE(std::any_of(m.points.begin(), m.points.end(), [&](Vec2 q) { return q == f; }))
          << "corner (" << f.x << ", " << f.y << ") is not a node";
    }
    double worst_boundary = 0, worst_outside = 0;
    for (const auto& e : m.boundary_edges)
      for (int32_t v : e)
        worst_boundary =
            std::max(worst_boundary, std::fabs(eval_sdf(c.geometry.view(), m.points[v])));
    for (Vec2 q : m.points) worst_outside = std::max(worst_outside, eval_sdf(c.geometry.view(), q));
    EXPECT_LE(worst_boundary, 1e-3 * h0);
    EXPECT_LE(worst_outside, 1e-3 * h0);
    EXPECT_GE(r.quality.q_min, 0.65);
    EXPECT_TRUE(r.stats.converged);
  }
}

// A square whose top side has two tiny V-notches, each three corners within 2e of each other,
// as a simplified coastline has: fixed all, they would make edges of e beside edges of h0.
TEST(CornerMeshes, CornersCloserThanAShareOfTheEdgeMakeNoSlivers) {
  const double h0 = 0.05, e = 0.1 * h0;
  std::vector<Vec2> outline = {{0, 0}, {1, 0}, {1, 1}};
  for (double x : {0.7, 0.3})
    for (Vec2 v : {Vec2{x + e, 1}, Vec2{x, 1 - e}, Vec2{x - e, 1}}) outline.push_back(v);
  outline.push_back({0, 1});
  Problem p;
  p.geometry = Shape{Polygon{outline}, "", ""};
  p.h0 = h0;
  const CompiledProblem c = compile_problem(p);
  // The square's corners and each notch's bottom, its sharpest corner.
  ASSERT_EQ(c.fixed_points.size(), 6u);
  ThreadPool pool(2);
  CpuEngine engine(pool);
  const MeshResult r = generate_mesh(c, engine, nullptr, nullptr);
  std::printf("[ measured ] notched square: nodes %zu, q_min %.3f, q_mean %.4f\n",
              r.mesh.points.size(), r.quality.q_min, r.quality.q_mean);
  EXPECT_TRUE(check_validity(r.mesh).valid());
  // With all ten corners fixed: q_min 0.67, q_mean 0.960.
  EXPECT_GE(r.quality.q_min, 0.75);
  EXPECT_GE(r.quality.q_mean, 0.975);
}

}  // namespace
}  // namespace meshd
