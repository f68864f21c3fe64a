// How fast a compiled distance can change: |d(p) - d(q)| <= L |p - q|.
//
// Every analytic primitive's distance is exact, so L = 1 for them, and min, max and negation keep
// it. A sampled grid's distance is its bilinear interpolant, whose slope within a cell is bounded
// by the largest difference of neighbouring samples over their spacing, per axis: more than 1
// where the data are not a true distance (a user's grid may be anything finite). The engines
// carry lower bounds on how far inside a node lies (clearance.cuh) with this constant.
#pragma once

#include "core/geometry/program.h"
#include "core/geometry/regular_grid.h"

namespace meshd {

// A bound on the slope of g's bilinear interpolant (the grid's own units).
double bilinear_lipschitz(const RegularGrid& g);

// L for `geometry`'s signed distance: the largest of 1 and every grid primitive's bound.
double distance_lipschitz(const Program& geometry);

}  // namespace meshd
