// The 3D DistMesh loop, in the order of distmeshnd.m, with the 2D loop's termination rule and
// density control (params3d.h has every constant).
#pragma once

#include <array>
#include <atomic>
#include <cstdint>
#include <vector>

#include "core/common/thread_pool.h"
#include "core/common/vec3.h"
#include "core/distmesh/observer.h"
#include "core/distmesh3d/domain3d.h"
#include "core/distmesh3d/params3d.h"
#include "core/distmesh3d/settle_surface3d.h"

namespace meshd {

class Engine3;

// The relaxed and optimised nodes and their tetrahedra, before the boundary faces are found.
struct Relaxed3 {
  std::vector<Vec3> points;  // #N by 3, the `fixed` fixed ones first, all used
  int64_t fixed = 0;
  int64_t unused_fixed = 0;  // fixed nodes that no tetrahedron kept (compact in distmesh3d.cpp)
  std::vector<std::array<int32_t, 4>> tets;  // #M by 4, positively oriented
  int iterations = 0;
  int retriangulations = 0;
  int partial_retriangulations = 0;   // of those, the ones that moved a few nodes (distmesh3d.cpp)
  int repaired_retriangulations = 0;  // and the ones the engine repaired (Engine3::repair_...)
  int repairs_refused = 0;            // repairs that left a kept tetrahedron turned (then built)
  int64_t removed = 0;          // nodes density control took out, and free nodes on another node
  SurfaceSettling surface;      // the surface nodes moved onto the boundary (settle_surface3d.h)
  int64_t optimizer_moves = 0;  // node moves of the sliver optimisation
  double t_relax = 0.0;         // seconds: steps 1-8 and the last triangulation, of which
  double t_initial = 0.0;       //   steps 1-2, the initial nodes,
  double t_triangulate = 0.0;   //   step 3, every triangulation (the last one too), of which
  double t_delaunay = 0.0;      //     CGAL's tetrahedra (built or moved, in canonical order),
  double t_steps = 0.0;         //   steps 4-8 and density control (the engine's share)
  double t_slivers = 0.0;       // seconds: the surface settling and the sliver optimisation
  bool converged = false;
};

// Meshes `domain` with tetrahedra of edge about h0 times its size field (h0 > 0, the request's
// length unit). `pool` may be null (the caller's thread alone); the result is the same for any
// number of threads. `observer` (may be null) hears of every step's progress, and gets the
// nodes and the kept tetrahedra after the iterations it asks a snapshot of
// (on_volume_snapshot); throws Error(kCancelled) within one step once `cancel` (may be null) is
// set.
// `engine` runs the steps (engine3.h); null: the CPU engine on `pool`. Triangulations and the
// finish run on the host, on `pool`.
Relaxed3 distmesh3d(const Domain3& domain, double h0, const Params3& params, ThreadPool* pool,
                    Observer* observer = nullptr, const std::atomic<bool>* cancel = nullptr,
                    Engine3* engine = nullptr);

}  // namespace meshd
