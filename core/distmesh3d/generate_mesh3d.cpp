#include "core/distmesh3d/generate_mesh3d.h"

#include <chrono>
#include <utility>

#include "core/distmesh3d/assemble_mesh3d.h"
#include "core/distmesh3d/distmesh3d.h"
#include "core/distmesh3d/geometry_domain3d.h"
#include "core/distmesh3d/surface_offset3d.h"

namespace meshd {

MeshResult3 generate_mesh3d(const CompiledProblem3& problem, ThreadPool* pool, Observer* observer,
                            const std::atomic<bool>* cancel, Engine3* engine) {
  const auto start = std::chrono::steady_clock::now();
  const double h0 = problem.h0;
  const GeometryDomain3 geometry(problem.geometry, h0, problem.size, problem.uniform,
                                 problem.auto_features, problem.exact_band);

  Relaxed3 relaxed =
      distmesh3d(geometry.domain(), h0, problem.params, pool, observer, cancel, engine);
  MeshResult3 out;
  out.stats.iterations = relaxed.iterations;
  out.stats.converged = relaxed.converged;
  out.stats.retriangulations = relaxed.retriangulations;
  out.stats.partial_retriangulations = relaxed.partial_retriangulations;
  out.stats.repaired_retriangulations = relaxed.repaired_retriangulations;
  out.stats.removed = relaxed.removed;
  out.stats.fixed = relaxed.fixed;
  out.stats.unused_fixed = relaxed.unused_fixed;
  out.stats.optimizer_moves = relaxed.optimizer_moves;
  out.stats.t_relax = relaxed.t_relax;
  out.stats.t_triangulation = relaxed.t_triangulate;
  out.stats.t_steps = relaxed.t_steps;
  out.stats.t_slivers = relaxed.t_slivers;
  out.mesh = assemble_mesh3d(geometry.domain(), std::move(relaxed));
  out.quality = summarize_tet_quality(out.mesh);
  out.quality.max_surface_offset =
      surface_offset3d(geometry.domain(), out.mesh.points, out.mesh.boundary_faces, 0.0).max;
  out.stats.t_total =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

MeshResult3 generate_mesh3d(const Problem3& problem, ThreadPool* pool, Observer* observer,
                            const std::atomic<bool>* cancel, Engine3* engine) {
  return generate_mesh3d(compile_problem3(problem), pool, observer, cancel, engine);
}

}  // namespace meshd
