// The first triangulation by construction (lattice triangles plus CGAL on the gaps' points)
// against CGAL on all the initial points: after Lawson's flips, the same triangles.
#include "core/distmesh/initial_triangulation.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "core/common/thread_pool.h"
#include "core/delaunay/exact_predicates.h"
#include "core/delaunay/lawson_repair.h"
#include "core/delaunay/triangle_neighbors.h"
#include "core/distmesh/compiled_problem.h"
#include "core/distmesh/cpu_engine.h"
#include "core/distmesh/node_estimate.h"
#include "core/geometry/sdf_eval.cuh"
#include "core/geometry/size_eval.cuh"
#include "tests/core/distmesh/benchmark_geometries.h"

namespace meshd {
namespace {

// Step 2's flags, as CpuEngine::initialize decides them.
std::vector<uint8_t> kept_flags(const CompiledProblem& c, const InitialGrid& g) {
  const int64_t total = g.nx * g.ny;
  const double geps = c.params.geps * c.h0;
  std::vector<double> size(total, 0.0);
  double h_min = INFINITY;
  for (int64_t k = 0; k < total; ++k) {
    const Vec2 q = initial_grid_point(g, k);
    if (eval_sdf(c.geometry.view(), q) >= geps) continue;
    size[k] = eval_size(c.size.view(), q);
    h_min = std::min(h_min, size[k]);
  }
  std::vector<uint8_t> kept(total, 0);
  for (int64_t k = 0; k < total; ++k) {
    if (size[k] <= 0.0 || !keep_by_size(c.seed, g, k, size[k], h_min)) continue;
    const Vec2 q = initial_grid_point(g, k);
    bool near_fixed = false;
    for (const Vec2 f : c.fixed_points) near_fixed |= norm(q - f) < 0.5 * c.h0 * size[k];
    kept[k] = !near_fixed;
  }
  return kept;
}

std::set<std::array<int32_t, 3>> canonical(const std::vector<std::array<int32_t, 3>>& tris) {
  std::set<std::array<int32_t, 3>> out;
  for (auto t : tris) {
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
    out.insert(t);
  }
  return out;
}

class InitialTriangulation : public ::testing::TestWithParam<std::string> {};

TEST_P(InitialTriangulation, FlipsToTheDelaunayTriangulationOfTheInitialPoints) {
  for (double nodes : {500.0, 4000.0}) {
    Problem p = testing::benchmark_problem(GetParam(), 0.1);
    p.h0 = h0_for_node_count(p, nodes);
    const CompiledProblem c = compile_problem(p);
    ThreadPool pool;
    CpuEngine cpu(pool);
    cpu.initialize(c);
    std::vector<Vec2> points;
    cpu.read_points(points);

    const InitialGrid grid = make_initial_grid(c.bbox, c.h0);
    Triangulation tri = initial_triangulation(grid, kept_flags(c, grid), c.fixed_points);
    ASSERT_FALSE(tri.triangles.empty()) << GetParam() << " at " << nodes;
    // The lattice's neighbours, known by construction, are those that matching edges finds.
    std::vector<std::array<int32_t, 3>> matched;
    ASSERT_TRUE(triangle_neighbors(tri.triangles, points.size(), matched));
    EXPECT_EQ(tri.neighbors, matched) << GetParam() << " at " << nodes;
    for (const auto& t : tri.triangles)
      ASSERT_GT(orientation_sign(points[t[0]], points[t[1]], points[t[2]]), 0);
    const std::vector<char> keep(tri.triangles.size(), 1), on_boundary(points.size(), 0);
    const RepairResult repair = lawson_repair(points, keep, on_boundary, tri);
    ASSERT_TRUE(repair.ok);
    const Triangulation reference = delaunay_triangulate(points);
    EXPECT_EQ(canonical(tri.triangles), canonical(reference.triangles))
        << GetParam() << " at " << nodes << " after " << repair.flips << " flips";
  }
}

INSTANTIATE_TEST_SUITE_P(Geometries, InitialTriangulation,
                         ::testing::Values("G1", "G2", "G3", "G4", "G5"));

}  // namespace
}  // namespace meshd
