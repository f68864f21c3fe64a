// Distance grids on the device: the GPU engine evaluates a grid's samples (uploaded with each
// program) as the CPU engine does, in the geometry and in the size field. Skips with a message
// where no CUDA device is visible (CI).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/common/thread_pool.h"
#include "core/distmesh/compiled_problem.h"
#include "core/distmesh/cpu_engine.h"
#include "core/distmesh/distmesh.h"
#include "core/distmesh/node_estimate.h"
#include "core/geometry/sdf_eval.cuh"
#include "core/mesh/validity.h"
#include "kernels/gpu_engine.h"
#include "tests/core/geometry/shape_builders.h"
#include "tests/kernels/gpu_agreement.h"

namespace meshd {
namespace {

// A rotated, scaled grid disk minus an exact disk, the edge graded towards a second grid (a
// small disk's distance), so that both programs carry samples.
CompiledProblem grid_problem(double nodes) {
  Problem p;
  p.geometry =
      testing::csg(CsgOp::kDifference,
                   {testing::transformed(testing::disk_grid(121, "organ"), 2.0, 0.3, {0.5, -0.25}),
                    testing::circle({0.9, -0.2}, 0.4, "hole")});
  DistanceSize graded;
  graded.shape = testing::distance_grid(
      [](Vec2 q) {
        return norm(q - Vec2{-0.8, 0.3}) - 0.2;
      },
      {-1.5, -1.5}, 0.05, 61, 61);
  graded.slope = 1.0;
  graded.h_max = 3.0;
  p.size.terms.push_back(graded);
  p.h0 = 1.0;
  p.h0 = h0_for_node_count(p, nodes);
  return compile_problem(p);
}

TEST(GpuDistanceGrid, OneStepOnRandomPointsMatchesTheCpu) {
  SKIP_WITHOUT_GPU();
  const CompiledProblem c = grid_problem(3000);
  ASSERT_FALSE(c.geometry.samples.empty());
  ASSERT_FALSE(c.size.shapes.samples.empty());
  const std::vector<Vec2> pts = testing::random_points(c, 3000, 3);
  ThreadPool pool;
  CpuEngine cpu(pool);
  GpuEngine gpu(0);
  testing::load_and_triangulate(c, pts, {&cpu, &gpu});
  const StepResult sc = cpu.move_points(), sg = gpu.move_points();
  EXPECT_NEAR(sc.max_move, sg.max_move, 1e-9);
  EXPECT_NEAR(sc.rms_move, sg.rms_move, 1e-9);
  std::vector<Vec2> a, b;
  cpu.read_points(a);
  gpu.read_points(b);
  ASSERT_EQ(a.size(), b.size());
  const testing::PointGaps gaps = testing::point_gaps(c, a, b);
  EXPECT_LT(gaps.interior, 1e-12 * c.h0);
  EXPECT_LT(gaps.boundary, 1e-6 * c.h0);
}

TEST(GpuDistanceGrid, WholeMeshMatchesTheCpuEngine) {
  SKIP_WITHOUT_GPU();
  const CompiledProblem c = grid_problem(5000);
  ThreadPool pool;
  CpuEngine cpu(pool);
  GpuEngine gpu(0);
  const MeshResult rc = generate_mesh(c, cpu, nullptr, nullptr);
  const MeshResult rg = generate_mesh(c, gpu, nullptr, nullptr);
  testing::expect_meshes_agree(rc, rg);
  EXPECT_EQ(rg.mesh.boundary_names, rc.mesh.boundary_names);
  double worst = 0.0;
  for (const auto& e : rg.mesh.boundary_edges)
    for (int32_t v : e)
      worst = std::max(worst, std::fabs(eval_sdf(c.geometry.view(), rg.mesh.points[v])));
  EXPECT_LE(worst, 1e-3 * c.h0);
}

}  // namespace
}  // namespace meshd
