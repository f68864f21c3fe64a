// How many nodes a 3D job will have, before it runs: the service's limits and the benchmark's
// --nodes both need it. The start keeps sqrt(2) / h0^3 nodes per unit volume where the size is
// smallest and (h_min / h)^3 of them elsewhere (initial_points3d.h); the relaxation keeps about
// as many.
#pragma once

#include <functional>

#include "core/common/vec3.h"

namespace meshd {

// What the estimate needs of a domain, from a 32^3 grid over its box.
struct VolumeSurvey3 {
  // The volume that the start fills at its finest density: the domain's volume weighted by
  // (h_min / h)^3; 0 when no grid cell centre lies inside.
  double weighted_volume = 0.0;
  // The largest depth (-distance) at a cell centre, and the cells' half diagonal: the domain's
  // largest inscribed ball has a radius between depth and depth + half_diagonal.
  double depth = 0.0;
  double half_diagonal = 0.0;
};

// distance: signed, negative inside; size: h(p) > 0, or empty for a uniform field.
VolumeSurvey3 survey_volume3d(const std::function<double(Vec3)>& distance,
                              const std::function<double(Vec3)>& size, const Box3& bounds);

// Nodes for edges of h0 at the finest size over `weighted_volume`.
double node_count3d(double weighted_volume, double h0);

// The h0 that gives about `nodes` nodes over `weighted_volume`.
double h0_for_node_count3d(double weighted_volume, double nodes);

}  // namespace meshd
