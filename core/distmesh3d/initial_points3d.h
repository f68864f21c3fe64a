// Steps 1-2 of the 3D loop: a body-centred cubic lattice over the domain's box, cut to the
// domain and thinned to the size field, the fixed nodes first.
//
// The lattice rather than distmeshnd's cubic grid: the Delaunay tetrahedra of a BCC lattice are
// all congruent (q = 0.87 and no dihedral under 60 degrees), while a cubic grid's are slivers
// and right-angled corners that the relaxation spends its first hundred steps undoing.
#pragma once

#include <cstdint>
#include <vector>

#include "core/common/vec3.h"
#include "core/distmesh3d/domain3d.h"

namespace meshd {

// The lattice's cube side for nodes h0 apart on average: a regular tetrahedron of edge h0 and
// the lattice give each node the same volume, a^3 / 2 = sqrt(2) h0^3 / 2 (six tetrahedra of
// volume h0^3 / (6 sqrt 2) a node).
double bcc_cube_side(double h0);

// The initial nodes, #N by 3: the domain's fixed nodes, then the lattice points with distance
// under geps h0 that are farther than half their size from every fixed node, each kept with
// probability (h_min / h)^3 by an ordered dither seeded by `seed` (the same nodes wherever it
// runs). h0 > 0 in the request's length unit.
std::vector<Vec3> initial_points3d(const Domain3& domain, double h0, double geps, uint64_t seed);

}  // namespace meshd
