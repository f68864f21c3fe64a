// Feature-size terms (feature_size.h): `elements` edges across a channel whatever its width,
// coarser where the domain is wide, never below h_min nor above h_max; through compile_problem
// and on a whole mesh with the CPU engine.
#include "core/geometry/feature_size.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/common/thread_pool.h"
#include "core/distmesh/compiled_problem.h"
#include "core/distmesh/cpu_engine.h"
#include "core/distmesh/distmesh.h"
#include "core/geometry/compile.h"
#include "core/geometry/size_eval.cuh"
#include "core/mesh/quality.h"
#include "core/mesh/validity.h"

namespace meshd {
namespace {

// The edge length h0 * h that a one-term field asks for at p.
double edge(const GridSize& g, double h0, Vec2 p) {
  SizeFieldSpec spec;
  spec.terms.push_back(g);
  return h0 * eval_size(compile_size_field(spec).view(), p);
}

TEST(FeatureSize, PutsTheElementsAcrossAChannel) {
  const Program channel = compile_geometry(Shape{Rectangle{{0, 0}, {8, 1}}, "", ""});
  const FeatureSize term{4, 0.5, 20};
  const double h0 = 0.05;
  const GridSize g = feature_size_grid(channel, term, {{0, 0}, {8, 1}}, 0.0125, h0);
  EXPECT_DOUBLE_EQ(g.scale, 0.5);
  // Width 1, 4 elements: edges of 0.25 across the whole width, away from the ends.
  for (double x : {2.0, 3.3, 5.1})
    for (double y : {0.05, 0.3, 0.5, 0.72, 0.95})
      EXPECT_NEAR(edge(g, h0, {x, y}), 0.25, 0.01) << x << " " << y;
  // The floor where the feature size vanishes (the corners), never below it anywhere.
  EXPECT_NEAR(edge(g, h0, {0, 0}), h0 * 0.5, 1e-9);
  EXPECT_GE(*std::min_element(g.values.begin(), g.values.end()), 1.0f);
}

TEST(FeatureSize, FinerInANeckThanInTheBulbs) {
  // Two disks of radius 1 joined by a neck 0.4 wide: 0.1 across the neck, 0.5 at a disk's centre
  // (its medial axis is the centre, 1 from the wall) with 4 elements.
  const Shape dumbbell{Csg{CsgOp::kUnion,
                           {Shape{Circle{{-2, 0}, 1}, "", ""}, Shape{Circle{{2, 0}, 1}, "", ""},
                            Shape{Rectangle{{-2, -0.2}, {2, 0.2}}, "", ""}}},
                       "", ""};
  const Program geometry = compile_geometry(dumbbell);
  const double h0 = 0.02;
  const GridSize g =
      feature_size_grid(geometry, FeatureSize{4, 1, 50}, {{-3, -1}, {3, 1}}, 0.01, h0);
  EXPECT_NEAR(edge(g, h0, {0, 0}), 0.1, 0.005);
  EXPECT_NEAR(edge(g, h0, {0, 0.15}), 0.1, 0.005);
  EXPECT_NEAR(edge(g, h0, {-2, 0}), 0.5, 0.025);
  EXPECT_NEAR(edge(g, h0, {2.5, 0}), 0.5, 0.025);  // halfway to the wall: 0.5 + 0.5 again
  // The cap: h_max 10 limits the disks' 0.5 to 0.2.
  const GridSize capped =
      feature_size_grid(geometry, FeatureSize{4, 1, 10}, {{-3, -1}, {3, 1}}, 0.01, h0);
  EXPECT_NEAR(edge(capped, h0, {-2, 0}), 0.2, 1e-6);
  EXPECT_NEAR(edge(capped, h0, {0, 0}), 0.1, 0.005);
}

TEST(FeatureSize, CompiledProblemSamplesItAndMeshesIt) {
  Problem p;
  p.geometry = Shape{Csg{CsgOp::kUnion,
                         {Shape{Circle{{-2, 0}, 1}, "", ""}, Shape{Circle{{2, 0}, 1}, "", ""},
                          Shape{Rectangle{{-2, -0.2}, {2, 0.2}}, "", ""}}},
                     "", ""};
  p.size.terms.push_back(FeatureSize{3, 1, 20});
  p.size.gradation = 0.3;  // from 0.4 / 3 in the neck to 2 / 3 in the bulbs, smoothly
  p.h0 = 0.02;
  const SizeFieldSpec sampled = sampled_size_field(p);
  ASSERT_EQ(sampled.terms.size(), 1u);
  EXPECT_TRUE(std::holds_alternative<GridSize>(sampled.terms[0]));
  p.size = sampled;
  const CompiledProblem c = compile_problem(p);
  EXPECT_NEAR(c.h0 * eval_size(c.size.view(), {0, 0}), 0.4 / 3, 0.01);
  ThreadPool pool;
  CpuEngine engine(pool);
  const MeshResult r = generate_mesh(c, engine, nullptr, nullptr);
  EXPECT_TRUE(check_validity(r.mesh).valid());
  EXPECT_GE(r.quality.q_min, 0.65);
  // At least 3 edges across the neck: the nodes on the line x = 0 (within a band) span it.
  int neck_nodes = 0;
  for (Vec2 q : r.mesh.points) neck_nodes += std::fabs(q.x) < 0.05;
  EXPECT_GE(neck_nodes, 3);
  std::printf(
      "[ measured ] dumbbell, 3 elements across: nodes %zu, q_min %.4f, %d nodes near x = 0\n",
      r.mesh.points.size(), r.quality.q_min, neck_nodes);
}

}  // namespace
}  // namespace meshd
