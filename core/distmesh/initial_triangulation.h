// The first triangulation of a job, mostly by construction: the initial points are an
// equilateral lattice (initial_points.cuh), whose triangles are Delaunay, minus the points that
// step 2 rejected, plus the fixed points.
//
// Invariants used: a lattice triangle whose three corners were all kept has an empty
// circumcircle among all lattice points, so also among the kept ones: it is a triangle of the
// Delaunay triangulation of the kept points. Call U the union of those triangles. The rest of
// the convex hull (pockets along U's outer boundary, holes in U, the surroundings of fixed
// points) is triangulated by CGAL on the points of U's boundary, the points in no lattice
// triangle and the fixed points alone: a few thousand at a million nodes, where triangulating
// everything takes about a second. The triangles of that small triangulation whose centroid
// lies outside U fill the gaps.
#pragma once

#include <cstdint>
#include <vector>

#include "core/common/vec2.h"
#include "core/delaunay/delaunay.h"
#include "core/distmesh/initial_points.cuh"

namespace meshd {

// A triangulation of the convex hull of the initial points, counter-clockwise, with neighbours
// (delaunay.h), Delaunay up to the few flips that exactly co-circular pockets may need. Point
// indices: fixed point f is f; kept grid point k is #fixed + (the number of kept grid points
// before k). Returns an empty triangulation when the checks (every edge used at most twice, in
// opposite directions; 2 N - 2 - hull triangles; fill triangles counter-clockwise) fail: the
// caller then triangulates from scratch.
//
// kept: #(nx ny) flags, 1 for grid points kept by step 2; fixed: #F by 2.
Triangulation initial_triangulation(const InitialGrid& grid, const std::vector<uint8_t>& kept,
                                    const std::vector<Vec2>& fixed);

}  // namespace meshd
