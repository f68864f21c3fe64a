// smooth_mean_quality: the finish's smoothing raises the mean quality and leaves the worst
// triangles, and the threshold under which they count as worst, to the optimisation after it.
#include "core/distmesh/smooth_mean_quality.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/common/thread_pool.h"
#include "core/distmesh/compiled_problem.h"
#include "core/distmesh/cpu_engine.h"
#include "core/distmesh/optimize_worst.h"
#include "core/geometry/sdf_eval.cuh"
#include "core/mesh/radius_ratio.cuh"
#include "tests/core/distmesh/benchmark_geometries.h"

namespace meshd {
namespace {

// A mesh part way through its relaxation: most triangles good, some still under the threshold.
MeshCopy relaxing_mesh(const CompiledProblem& problem) {
  ThreadPool pool(0);
  CpuEngine engine(pool);
  engine.initialize(problem);
  engine.retriangulate(true);
  for (int k = 0; k < 60; ++k) {
    engine.move_points();
    if (k % 5 == 4) engine.retriangulate(false);
  }
  MeshCopy copy;
  engine.read_mesh(copy);
  return copy;
}

std::vector<double> qualities(const std::vector<Vec2>& p,
                              const std::vector<std::array<int32_t, 3>>& triangles) {
  std::vector<double> q;
  for (const auto& t : triangles) q.push_back(oriented_radius_ratio(p[t[0]], p[t[1]], p[t[2]]));
  return q;
}

double mean(const std::vector<double>& v) {
  double sum = 0.0;
  for (double x : v) sum += x;
  return sum / static_cast<double>(v.size());
}

TEST(SmoothMeanQuality, RaisesTheMeanAndLeavesTheWorstTrianglesAsTheyWere) {
  for (const std::string id : {"G1", "G2", "G3", "G5"}) {
    const CompiledProblem problem = compile_problem(testing::benchmark_problem(id, 0.05));
    const MeshCopy copy = relaxing_mesh(problem);
    std::vector<Vec2> points = copy.points;
    const int64_t moves = smooth_mean_quality(problem, points, copy.triangles, copy.boundary);
    EXPECT_GT(moves, 0) << id;
    const std::vector<double> before = qualities(copy.points, copy.triangles);
    const std::vector<double> after = qualities(points, copy.triangles);
    EXPECT_GT(mean(after), mean(before) + 1e-3) << id;  // 0.0015-0.009 here
    int worst = 0;
    for (size_t t = 0; t < before.size(); ++t) {
      if (before[t] < kOptimizeBelowQuality) {
        ++worst;
        EXPECT_EQ(after[t], before[t]) << id << ", triangle " << t;
      } else {
        EXPECT_GE(after[t], kOptimizeBelowQuality) << id << ", triangle " << t;
      }
    }
    if (id != "G1") {
      EXPECT_GT(worst, 0) << id << ": no triangle under the threshold to keep";
    }
    for (size_t i = 0; i < problem.fixed_points.size(); ++i) {
      EXPECT_EQ(points[i].x, copy.points[i].x) << id << ", fixed node " << i;
      EXPECT_EQ(points[i].y, copy.points[i].y) << id << ", fixed node " << i;
    }
    // Every node stays in the domain; those on the boundary stay on it (as close as before).
    for (size_t i = 0; i < points.size(); ++i) {
      const double d = eval_sdf(problem.geometry.view(), points[i]);
      const double was = eval_sdf(problem.geometry.view(), copy.points[i]);
      EXPECT_LE(d, std::max(1e-4 * problem.h0, was)) << id << ", node " << i;
    }
  }
}

// Nodes that share no triangle move at once on the pool's threads: the same bits for any number.
TEST(SmoothMeanQuality, TheSameMovesOnAnyNumberOfThreads) {
  for (const std::string id : {"G2", "G5"}) {
    const CompiledProblem problem = compile_problem(testing::benchmark_problem(id, 0.05));
    const MeshCopy copy = relaxing_mesh(problem);
    std::vector<Vec2> alone = copy.points;
    const int64_t a = smooth_mean_quality(problem, alone, copy.triangles, copy.boundary);
    for (unsigned threads : {2u, 5u}) {
      ThreadPool pool(threads);
      std::vector<Vec2> pooled = copy.points;
      EXPECT_EQ(a, smooth_mean_quality(problem, pooled, copy.triangles, copy.boundary, &pool))
          << id << ", " << threads << " threads";
      for (size_t i = 0; i < alone.size(); ++i) {
        ASSERT_EQ(alone[i].x, pooled[i].x) << id << ", node " << i;
        ASSERT_EQ(alone[i].y, pooled[i].y) << id << ", node " << i;
      }
    }
  }
}

}  // namespace
}  // namespace meshd
