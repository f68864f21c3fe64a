// The clearance (clearance.cuh): a lower bound on how far inside a node lies, carried from step
// to step so that the engines skip the distance far from the boundary. It must never change a
// mesh, and its slope bound (lipschitz.h) must hold for grids that are no true distance.
#include "core/distmesh/clearance.cuh"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/common/thread_pool.h"
#include "core/distmesh/compiled_problem.h"
#include "core/distmesh/cpu_engine.h"
#include "core/distmesh/distmesh.h"
#include "core/distmesh/node_estimate.h"
#include "core/geometry/compile.h"
#include "core/geometry/lipschitz.h"
#include "core/geometry/sdf_eval.cuh"
#include "tests/core/distmesh/benchmark_geometries.h"
#include "tests/core/geometry/shape_builders.h"

namespace meshd {
namespace {

MeshResult mesh_with(const CompiledProblem& c) {
  ThreadPool pool(0);
  CpuEngine engine(pool);
  return generate_mesh(c, engine, nullptr, nullptr);
}

// The same mesh with every distance evaluated (an infinite slope: no clearance decides).
void expect_same_mesh_as_evaluating_everywhere(const Problem& p, const std::string& what) {
  const CompiledProblem carried = compile_problem(p);
  CompiledProblem evaluated = carried;
  evaluated.lipschitz = INFINITY;
  const MeshResult a = mesh_with(carried), b = mesh_with(evaluated);
  ASSERT_EQ(a.mesh.points.size(), b.mesh.points.size()) << what;
  for (size_t i = 0; i < a.mesh.points.size(); ++i) {
    ASSERT_EQ(a.mesh.points[i].x, b.mesh.points[i].x) << what << ", node " << i;
    ASSERT_EQ(a.mesh.points[i].y, b.mesh.points[i].y) << what << ", node " << i;
  }
  EXPECT_EQ(a.mesh.triangles, b.mesh.triangles) << what;
  EXPECT_EQ(a.stats.iterations, b.stats.iterations) << what;
}

TEST(Clearance, SkippingTheDistanceFarInsideLeavesEveryMeshBitForBit) {
  for (const char* id : {"G1", "G2", "G3", "G4", "G5"}) {
    Problem p = testing::benchmark_problem(id, 0.1);
    p.h0 = h0_for_node_count(p, 3000);
    expect_same_mesh_as_evaluating_everywhere(p, id);
  }
}

TEST(Clearance, AGridSteeperThanADistanceKeepsTheMeshToo) {
  // Three times a true distance: the interpolant's slope is about 3, and a bound that assumed 1
  // would skip nodes that the band around the boundary needs.
  Problem p;
  p.geometry = testing::distance_grid([](Vec2 q) { return 3.0 * (norm(q) - 1.0); }, {-1.5, -1.5},
                                      0.05, 61, 61, "steep");
  p.h0 = 1.0;
  p.h0 = h0_for_node_count(p, 3000);
  expect_same_mesh_as_evaluating_everywhere(p, "steep grid");
}

TEST(Lipschitz, AnalyticDistancesHaveSlopeOneAndGridsTheirSamplesSlope) {
  Problem disk = testing::benchmark_problem("G1", 0.1);
  EXPECT_EQ(distance_lipschitz(compile_geometry(disk.geometry)), 1.0);
  const Program steep = compile_geometry(testing::distance_grid(
      [](Vec2 q) { return 3.0 * (norm(q) - 1.0); }, {-1.5, -1.5}, 0.05, 61, 61, "steep"));
  const double l = distance_lipschitz(steep);
  EXPECT_GE(l, 3.0 * 0.99);
  EXPECT_LE(l, 3.0 * std::sqrt(2.0) * 1.01);
}

TEST(ClearanceRule, TheCarriedBoundNeverExceedsTheDistanceInside) {
  // A node wandering in a steep grid's disk: its clearance, carried and refreshed as the engines
  // do, stays at or below -d wherever it decides, for slopes above 1 too.
  const Program steep = compile_geometry(testing::distance_grid(
      [](Vec2 q) { return 3.0 * (norm(q) - 1.0); }, {-1.5, -1.5}, 0.05, 61, 61, "steep"));
  const ClearanceRule rule = ClearanceRule::make(distance_lipschitz(steep), 0.001, 0.06, 0.1);
  std::mt19937 rng(5);
  std::normal_distribution<double> step(0.0, 0.01);
  Vec2 q{0.0, 0.0};
  float clearance = 0.0f;
  int decided = 0;
  for (int i = 0; i < 20000; ++i) {
    const Vec2 move{step(rng), step(rng)};
    Vec2 next = q + move;
    if (norm(next) > 0.95) next = 0.5 * q;  // stay inside
    const double inside = rule.carried(clearance, norm(next - q));
    const double d = eval_sdf(steep.view(), next);
    if (rule.decides(inside)) {
      ++decided;
      ASSERT_LE(inside, -d) << "step " << i;
      clearance = round_down_to_float(inside);
    } else {
      clearance = round_down_to_float(-d);
    }
    ASSERT_LE(static_cast<double>(clearance), -d) << "step " << i;
    q = next;
  }
  EXPECT_GT(decided, 1000) << "the bound never decided";
}

}  // namespace
}  // namespace meshd
