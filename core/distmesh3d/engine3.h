// The interface between the 3D DistMesh loop (written once, in distmesh3d.cpp) and the machines
// that run its steps: the CPU engine (cpu_engine3.h) and the GPU engine in kernels/. The loop
// keeps the nodes and builds triangulations on the host; between two triangulations the engine
// owns the nodes, steps them and measures them, and gives them back when asked. An engine may
// also keep the last triangulation and repair it for the moved nodes (the GPU's flips), which
// spares the host a build.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "core/distmesh/step_rule.cuh"
#include "core/distmesh3d/domain3d.h"
#include "core/distmesh3d/params3d.h"
#include "core/distmesh3d/step3d.h"
#include "core/distmesh3d/topology3d.h"

namespace meshd {

class Engine3 {
 public:
  virtual ~Engine3() = default;
  virtual const char* name() const = 0;

  // A new job: its domain, its h0 (> 0, the request's length unit) and constants, all kept by
  // reference until the next begin. Throws Error(kInvalidArgument) for a domain the engine
  // cannot evaluate (the GPU's needs domain.program).
  virtual void begin(const Domain3& domain, double h0, const Params3& params) = 0;
  // After a triangulation: `nodes` (their at_triangulation just set) and `topology` are the
  // engine's, kept by reference, until the next start.
  virtual void start(Nodes3& nodes, const Topology3& topology) = 0;
  // Steps 4, 5, 7 and 8 (step3d.h) on the nodes.
  virtual StepResult step() = 0;
  // Step 6 on the last step's bars (crowded_nodes3d, step3d.h).
  virtual std::vector<int32_t> crowded_nodes() = 0;
  // Brings the nodes given to start up to date with every step since (nothing, when no step
  // ran since the last sync or start); the engine steps on from there (a snapshot reads them
  // between two steps).
  virtual void sync() = 0;

  // The Delaunay tetrahedra of all the `nodes` nodes (delaunay3d.h's, outside ones included),
  // just built on the host for the nodes about to be given to start: what a later repair starts
  // from. Nothing by default.
  virtual void keep_triangulation(const std::vector<std::array<int32_t, 4>>& all, int64_t nodes) {
    (void)all;
    (void)nodes;
  }
  // Nodes were removed, and the kept triangulation numbers them no more.
  virtual void forget_triangulation() {}
  // The kept triangulation repaired by flips for the nodes as the last step left them (after
  // sync), and kept for the next repair: conforming tetrahedra of all the nodes, locally Delaunay
  // wherever a flip could make them so, and positive but where flips could not mend them
  // (flip_repair3.h; the loop refuses a repair that leaves one of the tetrahedra it keeps
  // turned). Nothing where the engine has none or the flips do not end (the loop then builds on
  // the host). Nothing by default.
  virtual std::optional<std::vector<std::array<int32_t, 4>>> repair_triangulation() {
    return std::nullopt;
  }
};

}  // namespace meshd
