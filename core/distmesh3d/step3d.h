// Steps 4, 5, 7 and 8 of the 3D loop: bar forces, the Euler step and the projection onto the
// boundary, as distmeshnd.m takes them, with the measurements the loop's tests need.
#pragma once

#include <cstdint>
#include <vector>

#include "core/common/thread_pool.h"
#include "core/common/vec3.h"
#include "core/distmesh/step_rule.cuh"
#include "core/distmesh3d/domain3d.h"
#include "core/distmesh3d/params3d.h"
#include "core/distmesh3d/topology3d.h"

namespace meshd {

// The nodes of one 3D job and what they remember between steps.
struct Nodes3 {
  std::vector<Vec3> points;            // #N by 3, the first `fixed` never move
  std::vector<Vec3> momentum;          // #N by 3, the last step's move
  std::vector<Vec3> at_triangulation;  // #N by 3, the points at the last triangulation
  // #N, each node's mean bar length in the last triangulation (0 for a node in no bar): the
  // scale of drifted_nodes3d, kept with the nodes so that it outlives a renumbering.
  std::vector<double> spacing;
  int64_t fixed = 0;
};

// What the step left on the bars, for density control (step 6).
struct BarLengths {
  std::vector<double> length;   // #B, L
  std::vector<double> desired;  // #B, L0
};

// One step: forces of the bars of `topology` on nodes.points, the move (deltat F plus momentum
// times the last move), then the projection of nodes that left the domain back onto its
// boundary. Moves and drifts are measured in each node's own length (the mean L0 of its bars).
// h0 > 0 in the request's length unit.
StepResult step3d(const Domain3& domain, const Params3& params, double h0,
                  const Topology3& topology, Nodes3& nodes, BarLengths& bars, ThreadPool* pool);

// Step 6: the non-fixed ends of every bar with L0 > 2 L, increasing and unique.
std::vector<int32_t> crowded_nodes3d(const Topology3& topology, const BarLengths& bars,
                                     int64_t fixed);

// Sets nodes.spacing from the bars of `topology` (a triangulation of nodes.points).
void measure_spacing3d(const Topology3& topology, Nodes3& nodes);

// The free nodes that moved more than `fraction` of their spacing since their last
// triangulation, increasing: what a partial retriangulation moves.
std::vector<int32_t> drifted_nodes3d(const Nodes3& nodes, double fraction);

// Removes the nodes `indices` (increasing, none fixed) from `nodes`, keeping the others' order.
void remove_nodes3d(Nodes3& nodes, const std::vector<int32_t>& indices);

}  // namespace meshd
