// The multilevel loop (distmesh.cpp): a coarser level only prepares the next one's start, so it
// never spends the iterations that the problem itself needs.
#include <gtest/gtest.h>

#include "core/common/thread_pool.h"
#include "core/distmesh/compiled_problem.h"
#include "core/distmesh/cpu_engine.h"
#include "core/distmesh/distmesh.h"
#include "tests/core/distmesh/benchmark_geometries.h"

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

}  // namespace
}  // namespace meshd
