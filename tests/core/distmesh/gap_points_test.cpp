// Nodes where a coarser level's mesh left part of the domain without triangles (gap_points.h).
#include "core/distmesh/gap_points.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "core/common/thread_pool.h"
#include "core/distmesh/cpu_engine.h"
#include "core/distmesh/distmesh.h"
#include "core/distmesh/node_estimate.h"
#include "core/mesh/validity.h"

namespace meshd {
namespace {

Shape square_and_disk(Vec2 center, double radius) {
  return Shape{
      Csg{CsgOp::kUnion,
          {Shape{Rectangle{{0, 0}, {10, 10}}, "", ""}, Shape{Circle{center, radius}, "", ""}}},
      "", ""};
}

// The square [0, 10]^2 as two triangles.
const std::vector<Vec2> kSquare = {{0, 0}, {10, 0}, {10, 10}, {0, 10}};
const std::vector<std::array<int32_t, 3>> kSquareTriangles = {{0, 1, 2}, {0, 2, 3}};

CompiledProblem level_of(const Shape& geometry, double h0) {
  Problem p;
  p.geometry = geometry;
  p.h0 = h0;
  return compile_problem(p);
}

TEST(GapPoints, FillADiskThatTheCoarseMeshMissed) {
  const Vec2 center{13, 5};
  const CompiledProblem level = level_of(square_and_disk(center, 1.0), 0.25);
  const std::vector<Vec2> gaps =
      away_from_nodes(level, uncovered_grid_points(level, kSquare, kSquareTriangles), kSquare);
  // The disk's area over a grid point's, pi / (0.25^2 sqrt(3) / 2): about 58.
  EXPECT_GT(gaps.size(), 45u);
  EXPECT_LT(gaps.size(), 70u);
  for (const Vec2& q : gaps) EXPECT_LT(norm(q - center), 1.0) << q.x << ", " << q.y;
}

TEST(GapPoints, NoneWhereTheCoarseMeshCoversTheDomain) {
  const CompiledProblem level = level_of(Shape{Rectangle{{0, 0}, {10, 10}}, "", ""}, 0.25);
  EXPECT_TRUE(uncovered_grid_points(level, kSquare, kSquareTriangles).empty());
}

TEST(GapPoints, KeepHalfAnEdgeFromTheNodesThere) {
  const Vec2 center{13, 5};
  const CompiledProblem level = level_of(square_and_disk(center, 1.0), 0.25);
  std::vector<Vec2> nodes = kSquare;
  nodes.push_back(center);
  const std::vector<Vec2> gaps =
      away_from_nodes(level, uncovered_grid_points(level, kSquare, kSquareTriangles), nodes);
  EXPECT_FALSE(gaps.empty());
  for (const Vec2& q : gaps) EXPECT_GE(norm(q - center), 0.125) << q.x << ", " << q.y;
}

// The square [0, 10]^2 as 2 n^2 triangles, so that the grid's rows fall in many bands.
void square_grid_mesh(int n, std::vector<Vec2>& points, std::vector<std::array<int32_t, 3>>& tris) {
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) points.push_back({10.0 * i / n, 10.0 * j / n});
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int32_t a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      tris.push_back({a, b, d});
      tris.push_back({a, d, c});
    }
}

TEST(GapPoints, TheSameGapsOnAnyNumberOfThreads) {
  std::vector<Vec2> points;
  std::vector<std::array<int32_t, 3>> triangles;
  square_grid_mesh(40, points, triangles);
  triangles.erase(triangles.begin() + 1000, triangles.begin() + 1100);  // a gap inside too
  const CompiledProblem level = level_of(square_and_disk({13, 5}, 1.5), 0.05);
  const std::vector<Vec2> alone = uncovered_grid_points(level, points, triangles);
  ASSERT_GT(alone.size(), 1000u);
  for (unsigned threads : {2u, 5u}) {
    ThreadPool pool(threads);
    const std::vector<Vec2> pooled = uncovered_grid_points(level, points, triangles, &pool);
    ASSERT_EQ(pooled.size(), alone.size()) << threads << " threads";
    for (size_t k = 0; k < alone.size(); ++k) {
      ASSERT_EQ(pooled[k].x, alone[k].x) << k;
      ASSERT_EQ(pooled[k].y, alone[k].y) << k;
    }
  }
}

// Outside the domain the search skips the points of a row that the distance's bound puts outside
// too; a distance of unknown bound (an infinite Lipschitz constant) skips none: the same points.
TEST(GapPoints, SkippingTheOutsideChangesNothing) {
  std::vector<Vec2> points;
  std::vector<std::array<int32_t, 3>> triangles;
  square_grid_mesh(40, points, triangles);
  triangles.erase(triangles.begin() + 1000, triangles.begin() + 1100);
  const CompiledProblem level = level_of(square_and_disk({13, 5}, 1.5), 0.05);
  CompiledProblem unbounded = level;
  unbounded.lipschitz = INFINITY;
  const std::vector<Vec2> skipping = uncovered_grid_points(level, points, triangles);
  const std::vector<Vec2> every = uncovered_grid_points(unbounded, points, triangles);
  ASSERT_EQ(skipping.size(), every.size());
  for (size_t k = 0; k < every.size(); ++k) {
    ASSERT_EQ(skipping[k].x, every[k].x) << k;
    ASSERT_EQ(skipping[k].y, every[k].y) << k;
  }
}

// Through the multilevel loop: a disk narrower than the coarsest level's edge, beside a square
// meshed in three levels, gets no triangle at the coarse levels; the finest level fills it.
TEST(GapPoints, AMultilevelRunMeshesADiskUnderItsCoarsestResolution) {
  const Vec2 center{10.5, 5};
  const double radius = 0.08;
  Problem p;
  p.geometry = square_and_disk(center, radius);
  p.h0 = 1.0;
  p.h0 = h0_for_node_count(p, 40000);
  p.params.multilevel = Params::Multilevel::kOn;
  const CompiledProblem c = compile_problem(p);
  ThreadPool pool;
  CpuEngine engine(pool);
  const MeshResult r = generate_mesh(c, engine, nullptr, nullptr);
  std::printf("[ measured ] %d levels, h0 %.4f, %zu nodes, %lld gap nodes\n", r.stats.levels, c.h0,
              r.mesh.points.size(), static_cast<long long>(r.stats.gap_nodes));
  ASSERT_GE(r.stats.levels, 3);
  ASSERT_GT(c.h0 * 4, 2 * radius);  // the coarsest edge spans the disk
  EXPECT_GT(r.stats.gap_nodes, 0);
  EXPECT_TRUE(check_validity(r.mesh).valid());
  // The disk lies apart from the square: the triangles beyond x = 10 cover it.
  double covered = 0;
  for (const auto& t : r.mesh.triangles) {
    const Vec2 a = r.mesh.points[t[0]], b = r.mesh.points[t[1]], d = r.mesh.points[t[2]];
    if ((a.x + b.x + d.x) / 3 <= 10) continue;
    covered += 0.5 * ((b.x - a.x) * (d.y - a.y) - (b.y - a.y) * (d.x - a.x));
  }
  EXPECT_GT(covered, 0.8 * std::numbers::pi * radius * radius);
}

}  // namespace
}  // namespace meshd
