// A whole mesh with a gridded size field on the CPU engine: a 2 x 1 rectangle whose grid asks
// for edges growing from h0 on the left to 3 h0 on the right. The mesh is valid and good, its
// edges follow the grid, and its node count the estimate; with a gradation, the edges grow no
// faster than it allows.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <vector>

#include "core/common/thread_pool.h"
#include "core/distmesh/compiled_problem.h"
#include "core/distmesh/cpu_engine.h"
#include "core/distmesh/distmesh.h"
#include "core/distmesh/node_estimate.h"
#include "core/geometry/size_eval.cuh"
#include "core/mesh/quality.h"
#include "core/mesh/validity.h"

namespace meshd {
namespace {

// h = 1 + x on [0, 2] x [0, 1], sampled on a 9 x 3 grid.
Problem ramp_problem(double h0) {
  Problem p;
  p.geometry = Shape{Rectangle{{0, 0}, {2, 1}}, "box", ""};
  GridSize g;
  g.origin = {0, 0};
  g.spacing = {0.25, 0.5};
  g.nx = 9;
  g.ny = 3;
  for (uint32_t j = 0; j < g.ny; ++j)
    for (uint32_t i = 0; i < g.nx; ++i) g.values.push_back(1.0f + 0.25f * i);
  p.size.terms.push_back(g);
  p.h0 = h0;
  return p;
}

struct EdgeStats {
  double left = 0, right = 0;  // mean edge length with its midpoint at x < 0.5, at x > 1.5
  double mean_ratio = 0;       // mean of length / (h0 h(midpoint)) over all edges
};

EdgeStats edge_stats(const Mesh& m, const CompiledProblem& c) {
  EdgeStats s;
  int nl = 0, nr = 0, n = 0;
  for (const auto& t : m.triangles)
    for (int k = 0; k < 3; ++k) {
      const Vec2 a = m.points[t[k]], b = m.points[t[(k + 1) % 3]];
      const Vec2 mid = 0.5 * (a + b);
      const double len = norm(a - b);
      s.mean_ratio += len / (c.h0 * eval_size(c.size.view(), mid));
      ++n;
      if (mid.x < 0.5) s.left += len, ++nl;
      if (mid.x > 1.5) s.right += len, ++nr;
    }
  s.left /= nl;
  s.right /= nr;
  s.mean_ratio /= n;
  return s;
}

TEST(GridSizeMesh, EdgesFollowTheGrid) {
  const CompiledProblem c = compile_problem(ramp_problem(0.04));
  ThreadPool pool;
  CpuEngine engine(pool);
  const MeshResult r = generate_mesh(c, engine, nullptr, nullptr);
  const ValidityReport report = check_validity(r.mesh);
  EXPECT_TRUE(report.valid()) << (report.problems.empty() ? "" : report.problems.front());
  EXPECT_GE(r.quality.q_min, 0.65);
  EXPECT_GE(r.quality.q_mean, 0.95);
  EXPECT_NEAR(mesh_area(r.mesh), 2.0, 0.005 * 2.0);
  const double nodes = estimate_node_count(c);
  EXPECT_NEAR(static_cast<double>(r.mesh.points.size()) / nodes, 1.0, 0.10);
  // Mean h over x < 0.5 is 1.25, over x > 1.5 it is 2.75: the edges' ratio 2.2.
  const EdgeStats s = edge_stats(r.mesh, c);
  std::printf(
      "[ measured ] grid ramp: nodes %zu (estimate %.0f), q_min %.4f, q_mean %.4f, "
      "right / left edges %.3f, length / wanted %.3f\n",
      r.mesh.points.size(), nodes, r.quality.q_min, r.quality.q_mean, s.right / s.left,
      s.mean_ratio);
  EXPECT_NEAR(s.right / s.left, 2.2, 0.2 * 2.2);
  EXPECT_NEAR(s.mean_ratio, 1.0, 0.2);
}

TEST(GridSizeMesh, GradationBoundsTheEdgesGrowth) {
  // The ramp grows the edge by h0 = 0.04 per unit; a gradation of 0.01 lets it grow from 0.04
  // on the left to 0.04 + 0.01 * 2 = 0.06 on the right, not 0.12.
  Problem p = ramp_problem(0.04);
  p.size.gradation = 0.01;
  p.size = sampled_size_field(p);
  const CompiledProblem c = compile_problem(p);
  EXPECT_NEAR(c.h0 * eval_size(c.size.view(), {2, 0.5}), 0.06, 1e-4);
  ThreadPool pool;
  CpuEngine engine(pool);
  const MeshResult r = generate_mesh(c, engine, nullptr, nullptr);
  EXPECT_TRUE(check_validity(r.mesh).valid());
  EXPECT_GE(r.quality.q_min, 0.65);
  const EdgeStats s = edge_stats(r.mesh, c);
  std::printf("[ measured ] graded grid ramp: nodes %zu, q_min %.4f, right / left edges %.3f\n",
              r.mesh.points.size(), r.quality.q_min, s.right / s.left);
  // Mean h0 h over x > 1.5 is 0.04 + 0.01 * 1.75 = 0.0575, over x < 0.5 it is 0.0425.
  EXPECT_NEAR(s.right / s.left, 0.0575 / 0.0425, 0.15 * 0.0575 / 0.0425);
}

}  // namespace
}  // namespace meshd
