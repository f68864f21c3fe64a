// The multilevel loop (distmesh.cpp): a coarser level only prepares the next one's start, so it
// never spends the iterations that the problem itself needs.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/common/thread_pool.h"
#include "core/distmesh/compiled_problem.h"
#include "core/distmesh/cpu_engine.h"
#include "core/distmesh/distmesh.h"
#include "core/distmesh/node_estimate.h"
#include "core/mesh/validity.h"
#include "tests/core/distmesh/benchmark_geometries.h"
#include "tests/core/distmesh/forwarding_engine.h"

namespace meshd {
namespace {

TEST(Multilevel, CoarserLevelsLeaveTheProblemItselfHalfTheIterations) {
  // G5 at about 10k nodes meshes in two levels; 40 iterations settle neither of them.
  Problem p = testing::benchmark_problem("G5", 0.012);
  p.params.multilevel = Params::Multilevel::kOn;
  p.params.max_iterations = 40;
  p.params.cleanup = false;
  const CompiledProblem c = compile_problem(p);
  ThreadPool pool;
  CpuEngine engine(pool);
  const MeshResult r = generate_mesh(c, engine, nullptr, nullptr);
  ASSERT_EQ(r.stats.levels, 2);
  EXPECT_EQ(r.stats.iterations, 40);
  EXPECT_FALSE(r.stats.converged);
  // (coarse iterations * coarse nodes + fine iterations * fine nodes) / fine nodes: at least
  // the 20 iterations the problem itself keeps (had the coarse level taken all 40, about 11).
  EXPECT_GE(r.stats.equivalent_iterations, 20.0);
}

// Every level keeps every fixed node, so a level with fewer nodes than a few per fixed node is
// mostly fixed nodes, denser than its size field; its L0 scale follows its own density and each
// refinement passes the excess on. A square with 3,000 fixed nodes on its sides, a quarter of
// the edge apart, aimed at about 40k nodes: meshed in one level, with about the nodes estimated
// (in three levels, the coarsest aimed at 2,500 nodes beside its 3,000 fixed ones, it took six
// times as long and came out with 5% more nodes).
TEST(Multilevel, NoLevelIsMostlyFixedNodes) {
  Problem p;
  p.geometry = Shape{Rectangle{{0, 0}, {1, 1}}, "", ""};
  p.h0 = 1.0;
  p.h0 = h0_for_node_count(p, 40000);
  p.params.multilevel = Params::Multilevel::kOn;
  p.params.cleanup = false;
  for (int i = 0; i < 750; ++i) {
    const double t = i / 750.0;
    p.fixed_points.insert(p.fixed_points.end(), {{t, 0}, {1, t}, {1 - t, 1}, {0, 1 - t}});
  }
  const CompiledProblem c = compile_problem(p);
  ThreadPool pool;
  CpuEngine engine(pool);
  const MeshResult r = generate_mesh(c, engine, nullptr, nullptr);
  const double expected = estimate_node_count(c);
  std::printf("[ measured ] %d levels, %zu nodes, %.0f estimated, %zu fixed\n", r.stats.levels,
              r.mesh.points.size(), expected, c.fixed_points.size());
  EXPECT_EQ(r.stats.levels, 1);
  EXPECT_LT(static_cast<double>(r.mesh.points.size()), 1.3 * expected);
  EXPECT_TRUE(check_validity(r.mesh).valid());
}

// A coarser level whose rms move stops falling fast (here: never reported under 10 dptol, as
// where nodes oscillate across channels narrower than its edges) ends 100 steps after its last
// progress, instead of spending its share of max_iterations; the problem itself then settles as
// usual.
class StuckCoarseLevelEngine final : public testing::ForwardingEngine {
 public:
  StuckCoarseLevelEngine(ThreadPool& pool, double floor)
      : ForwardingEngine(pool), floor_(floor) {}
  int64_t load_points(const CompiledProblem& p, const std::vector<Vec2>& pts) override {
    coarse_ = false;  // the next level starts
    return ForwardingEngine::load_points(p, pts);
  }
  StepResult move_points() override {
    StepResult r = cpu_.move_points();
    if (coarse_) {
      r.rms_move = std::max(r.rms_move, floor_);
      coarse_steps.push_back(r);
    }
    return r;
  }
  std::vector<StepResult> coarse_steps;

 private:
  double floor_;
  bool coarse_ = true;
};

TEST(Multilevel, ACoarserLevelWhoseRmsMoveStopsFallingEndsThere) {
  Problem p = testing::benchmark_problem("G5", 0.012);
  p.params.multilevel = Params::Multilevel::kOn;
  p.params.cleanup = false;
  const CompiledProblem c = compile_problem(p);
  ThreadPool pool;
  StuckCoarseLevelEngine engine(pool, 10.0 * c.params.dptol);
  const MeshResult r = generate_mesh(c, engine, nullptr, nullptr);
  ASSERT_EQ(r.stats.levels, 2);
  EXPECT_TRUE(r.stats.converged);
  ASSERT_FALSE(engine.coarse_steps.empty());
  EXPECT_LT(engine.coarse_steps.size(), 2000u);
  // It ended at the 100th step after the last that took the rms move under 3/4 of its record.
  double record = INFINITY;
  int stalled = 0;
  for (const StepResult& s : engine.coarse_steps) {
    const bool progress = s.rms_move < 0.75 * record;
    stalled = progress ? 0 : stalled + 1;
    if (progress) record = s.rms_move;
  }
  EXPECT_EQ(stalled, 100);
  EXPECT_TRUE(check_validity(r.mesh).valid());
}

}  // namespace
}  // namespace meshd
