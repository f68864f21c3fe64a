// The finish's node moves (node_moves.h) keep every triangle inside the domain, as the centroid
// filter left it, where spits of land narrower than an edge reach into the water: a coastline's
// finish had carried boundary nodes round such tips and covered 125 of them with triangles.
#include "core/distmesh/node_moves.h"

#include <gtest/gtest.h>

#include <cstdio>

#include "core/common/thread_pool.h"
#include "core/distmesh/cpu_engine.h"
#include "core/distmesh/distmesh.h"
#include "core/geometry/sdf_eval.cuh"
#include "core/mesh/validity.h"

namespace meshd {
namespace {

// The square [0, 10]^2 less spits from its lower side: 0.1 wide at their base, leaning, with
// sharp tips 2 to 6 up, against an edge of 0.4.
Shape square_with_spits() {
  std::vector<Shape> spits;
  for (int k = 0; k < 9; ++k) {
    const double x = 1.0 + k, lean = 0.3 * (k % 3 - 1), height = 2.0 + 0.5 * k;
    spits.push_back(
        Shape{Polygon{{{x - 0.05, -1.0}, {x + 0.05, -1.0}, {x + lean, height}}}, "", ""});
  }
  const Shape land{Csg{CsgOp::kUnion, std::move(spits)}, "", ""};
  return Shape{Csg{CsgOp::kDifference, {Shape{Rectangle{{0, 0}, {10, 10}}, "", ""}, land}}, "", ""};
}

TEST(NodeMoves, TheFinishKeepsEveryTriangleOffTheSpitsOfLand) {
  Problem p;
  p.geometry = square_with_spits();
  p.h0 = 0.4;
  const CompiledProblem c = compile_problem(p);
  ThreadPool pool;
  CpuEngine engine(pool);
  const MeshResult r = generate_mesh(c, engine, nullptr, nullptr);
  std::printf("[ measured ] %zu nodes, %lld smoothing moves, %lld optimising moves\n",
              r.mesh.points.size(), static_cast<long long>(r.stats.smoothed_moves),
              static_cast<long long>(r.stats.optimized_moves));
  ASSERT_GT(r.stats.smoothed_moves + r.stats.optimized_moves, 0);
  EXPECT_TRUE(check_validity(r.mesh).valid());
  const double geps = c.params.geps * c.h0;
  int outside = 0;
  for (const auto& t : r.mesh.triangles) {
    const Vec2 centroid =
        (1.0 / 3.0) * (r.mesh.points[t[0]] + r.mesh.points[t[1]] + r.mesh.points[t[2]]);
    const double d = eval_sdf(c.geometry.view(), centroid);
    if (!(d < -geps)) {
      ++outside;
      ADD_FAILURE() << "triangle's centroid at (" << centroid.x << ", " << centroid.y << ") lies "
                    << d << " outside";
    }
  }
  EXPECT_EQ(outside, 0);
}

}  // namespace
}  // namespace meshd
