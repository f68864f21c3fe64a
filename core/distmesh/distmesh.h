// The DistMesh loop (Persson & Strang, distmesh2d.m), written once over the Engine interface.
#pragma once

#include <atomic>

#include "core/distmesh/compiled_problem.h"
#include "core/distmesh/engine.h"
#include "core/distmesh/observer.h"
#include "core/mesh/mesh.h"
#include "core/mesh/quality.h"

namespace meshd {

struct RunStats {
  int iterations = 0;                // of the main loop over all levels, clean-up not included
  int levels = 1;                    // multilevel: meshes at h0 * 2^k, k = levels-1 .. 0
  double equivalent_iterations = 0;  // sum of iterations * nodes of each level / final nodes
  bool converged = false;            // false: stopped at max_iterations
  int retriangulations = 0;          // all triangulations, the first included
  int full_triangulations = 0;
  int64_t flips = 0;
  int repair_fallbacks = 0;     // repairs that rebuilt from scratch instead
  int fold_refills = 0;         // repairs that met turned-over triangles and mended them locally
  int64_t density_removed = 0;  // points removed by density control
  int64_t cleanup_removed = 0;  // points removed by the boundary clean-up
  int64_t gap_nodes = 0;        // nodes added where a coarser level left no mesh (gap_points.h)
  int64_t trapped_removed = 0;  // interior nodes of three triangles the finish removed
  int cleanup_iterations = 0;
  int64_t smoothed_moves = 0;   // node moves of the finish's smoothing (smooth_mean_quality.h)
  int64_t optimized_moves = 0;  // node moves of the worst-element optimisation
  // Seconds per phase; total is the wall time of generate_mesh. t_full_triangulation is the part
  // of t_triangulation spent in triangulations from scratch; t_finish is the last triangulation,
  // the smoothing, the worst-element optimisation and the assembly of the result. Steps that an
  // engine runs behind a retriangulation's repair (Engine::retriangulate_and_move) count in
  // t_triangulation.
  double t_initial = 0, t_triangulation = 0, t_full_triangulation = 0, t_forces = 0, t_density = 0,
         t_cleanup = 0, t_finish = 0, t_total = 0;
};

struct MeshResult {
  Mesh mesh;
  RunStats stats;
  QualityStats quality;
};

// Meshes `problem` on `engine`. Reports through `observer` (may be null) and stops with
// Error(kCancelled) within one iteration once `cancel` (may be null) is set.
MeshResult generate_mesh(const CompiledProblem& problem, Engine& engine, Observer* observer,
                         const std::atomic<bool>* cancel);

}  // namespace meshd
