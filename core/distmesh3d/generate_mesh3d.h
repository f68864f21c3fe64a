// One 3D job from its (compiled) Problem3 to the finished tetrahedral mesh and its report: the
// geometry compiled, the loop (distmesh3d.h), the boundary faces and their groups, the quality.
// What the service's workers and the benchmark run (the twin of generate_mesh in 2D).
#pragma once

#include <atomic>
#include <cstdint>

#include "core/common/thread_pool.h"
#include "core/distmesh/observer.h"
#include "core/distmesh3d/compiled_problem3d.h"
#include "core/distmesh3d/problem3d.h"
#include "core/mesh3d/tet_mesh.h"
#include "core/mesh3d/tet_quality.h"

namespace meshd {

class Engine3;

struct RunStats3 {
  int iterations = 0;
  bool converged = false;
  int retriangulations = 0;
  int partial_retriangulations = 0;   // of those, moves of a few nodes in the kept triangulation
  int repaired_retriangulations = 0;  // and repairs by the engine (the GPU's flips)
  int64_t removed = 0;  // nodes density control took out, and free nodes on another node
  int64_t fixed = 0;    // fixed nodes kept (sharp corners and edge samples)
  int64_t unused_fixed = 0;
  int64_t optimizer_moves = 0;
  double t_relax = 0.0;          // seconds
  double t_triangulation = 0.0;  // seconds of t_relax spent triangulating
  double t_steps = 0.0;          // seconds of t_relax spent in the engine's steps
  double t_slivers = 0.0;        // seconds
  double t_total = 0.0;          // seconds, the sharp features and boundary faces included
};

struct MeshResult3 {
  TetMesh mesh;
  RunStats3 stats;
  TetQualityStats quality;
};

// Meshes `problem`. h0 and the size field are applied so that the edge length is about
// h0 * h(p) where h is at its smallest bound. pool: may be null; observer: may be null;
// Error(kCancelled) within one step once `cancel` (may be null) is set. `engine` runs the steps
// (engine3.h); null: the CPU engine on `pool`.
MeshResult3 generate_mesh3d(const CompiledProblem3& problem, ThreadPool* pool, Observer* observer,
                            const std::atomic<bool>* cancel, Engine3* engine = nullptr);
// The same, compiling `problem` first (compile_problem3).
MeshResult3 generate_mesh3d(const Problem3& problem, ThreadPool* pool, Observer* observer,
                            const std::atomic<bool>* cancel, Engine3* engine = nullptr);

}  // namespace meshd
