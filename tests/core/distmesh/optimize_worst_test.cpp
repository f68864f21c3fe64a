// optimize_worst_elements: the clean-up's last step may move nodes, but never leaves a triangle
// flatter than it found it.
#include "core/distmesh/optimize_worst.h"

#include <gtest/gtest.h>

#include "core/distmesh/assemble_mesh.h"
#include "core/distmesh/compiled_problem.h"
#include "core/mesh/boundary.h"
#include "core/mesh/validity.h"

namespace meshd {
namespace {

// UTM-sized coordinates, where a flat triangle's round-off is far above 1e-16 of its size.
Vec2 at(double x, double y) { return Vec2{6.0e5, 6.6e6} + 100.0 * Vec2{x, y}; }

// A node of the mesh's boundary that lies inside the domain is snapped onto the boundary. When
// the opposite edge of its triangle already lies there, the snap flattens that triangle to
// round-off, and its sign is the round-off's: some of these positions would come out with a
// positive area far below any real triangle's, which no later move can undo.
TEST(OptimizeWorst, SnappingANodeOntoTheBoundaryNeverFlattensItsTriangle) {
  Problem p;
  p.h0 = 100.0;
  p.auto_corners = false;
  p.geometry = Shape{Polygon{{at(0, 0), at(3, 1), at(0, 3)}}, "", ""};
  const CompiledProblem problem = compile_problem(p);
  const std::vector<std::array<int32_t, 3>> triangles = {{0, 1, 2}};
  for (int k = 0; k < 64; ++k) {
    // a and b on the slanted side, v inside just above it, between them.
    const Vec2 a = at(0.3, 0.1), b = at(2.7, 0.9);
    const double s = 0.2 + 0.6 * k / 63.0;
    const Vec2 v = a + s * (b - a) + 100.0 * Vec2{-0.01, 0.03};
    std::vector<Vec2> points = {a, b, v};
    optimize_worst_elements(problem, points, triangles, boundary_half_edges(triangles));
    const Mesh mesh = assemble_mesh(problem, points, triangles, boundary_half_edges(triangles));
    const ValidityReport report = check_validity(mesh);
    EXPECT_TRUE(report.valid()) << "v at s = " << s << ": " << report.problems.front();
  }
}

}  // namespace
}  // namespace meshd
