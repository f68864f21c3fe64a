#include "core/distmesh/engine.h"

#include "core/distmesh/refine.h"
#include "core/distmesh/spatial_order.h"
#include "core/mesh/boundary.h"

namespace meshd {

int64_t Engine::refine(const CompiledProblem& finer) {
  std::vector<Vec2> points;
  std::vector<std::array<int32_t, 3>> triangles;
  read_points(points);
  read_triangles(triangles);
  // The split triangles are dropped: CGAL's triangulation of the new points costs the CPU engine
  // about what completing and flipping them would.
  refine_by_midpoints(finer, points, triangles);
  triangles.clear();
  hilbert_order(points, static_cast<int32_t>(finer.fixed_points.size()), triangles);
  return load_points(finer, points);
}

void Engine::read_mesh(MeshCopy& copy) {
  read_points(copy.points);
  read_triangles(copy.triangles);
  copy.boundary = boundary_half_edges(copy.triangles);
  copy.below.reset();
  copy.tidy = false;
}

QualityStats Engine::measure_quality(const Mesh& mesh, bool /*moved*/) {
  return summarize_quality(mesh);
}

void Engine::move_points_until(const StepRule& rule, int first_iteration, int limit,
                               std::vector<StepResult>& steps) {
  Settling settling = rule.settling;
  for (int k = 0; k < limit; ++k) {
    steps.push_back(move_points());
    settling = rule.settle(settling, steps.back());
    if (rule.stops(steps.back(), first_iteration + k, settling)) return;
  }
}

std::optional<TopologyStats> Engine::retriangulate_and_move(const StepRule& /*rule*/,
                                                            int /*first_iteration*/, int /*limit*/,
                                                            std::vector<StepResult>& /*steps*/) {
  return std::nullopt;
}

}  // namespace meshd
