// Signed distance given as samples on a regular grid (Op::kGrid, DistMesh's dmatrix), e.g. the
// distance transform of a segmented image.
//
// What "distance" means here: the bilinear interpolant of the samples, exact only as the data
// are. A true distance sampled at spacing h comes back within O(h^2) times the boundary's
// curvature (more near the medial axis and at the boundary's own corners, where the distance is
// not smooth); a distance transform of a binary mask is off by up to a pixel wherever the mask
// is. The domain is the interpolant's negative set within the grid's box:
//
//   d(p) = max(bilinear(clamp(p)), box(p))
//
// with box the exact signed distance to the grid's box. Outside the box that never overstates
// how close p lies to the domain: clamping onto a convex box moves p nearer to every point of
// it, so the value at the clamped point does not exceed the (interpolated) distance from p.
//
// Projection onto the boundary (projection.cuh) needs no gradient of its own here: along x at
// fixed y, and along y at fixed x, the bilinear interpolant is linear within a cell, so the
// forward differences there are the exact partial derivatives (one-sided where a step crosses a
// cell's edge, where the interpolant has a kink anyway).
//
// Parameters (program.h): the grid header (regular_grid.h), then tx ty cos sin scale: world p
// maps to R(-angle) (p - t) / scale in the grid's frame, and distances there scale by `scale`.
#pragma once

#include <cmath>

#include "core/common/hd.h"
#include "core/common/vec2.h"
#include "core/geometry/regular_grid.h"

namespace meshd {

// The grid's frame of world point p; q points at the grid's parameters. sdf_eval.cuh's sdf_grid
// evaluates the distance there.
MESHD_HD inline Vec2 grid_local(const double* q, Vec2 p) {
  const double* t = q + kGridParams;
  const double dx = p.x - t[0], dy = p.y - t[1];
  return {(t[2] * dx + t[3] * dy) / t[4], (-t[3] * dx + t[2] * dy) / t[4]};
}

}  // namespace meshd
