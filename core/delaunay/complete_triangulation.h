// Completion of a partial triangulation into one of the convex hull of all its points, with
// CGAL on the few points that bound the gaps rather than on all of them.
//
// Call U the union of the given triangles. The gaps (the rest of the convex hull: pockets
// along U's outer boundary, holes in U, the surroundings of points in no triangle) are
// triangulated by CGAL on the points of U's boundary, the points in no triangle and the first
// `always_gap` points: a few thousand at a million nodes, where triangulating everything takes
// about a second. That triangulation is constrained to contain U's boundary edges (walls): a
// plain Delaunay one need not, even where U is Delaunay, when the gaps' points are co-circular
// (a hole's boundary nodes all lie on its circle). Its triangles on the walls' far side, and
// those reached from there without crossing a wall, fill the gaps. Where U's triangles are only
// nearly Delaunay (points that moved since) the checks below usually still pass, and Lawson's
// flips finish the job. Where they fail (walls that cross by rounding where flat triangles along
// a straight boundary were dropped), the triangles next to the gaps are given up and the gaps
// filled again, at most twice.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/common/vec2.h"
#include "core/delaunay/delaunay.h"

namespace meshd {

// Returns a triangulation of the convex hull of `points` (#N by 2) that contains every triangle
// of `partial` (#M by 3, counter-clockwise, non-overlapping; its neighbours -1 across U's
// boundary, as triangle_neighbors.h finds them or as they survive from the triangulation it was
// cut from), with neighbours (delaunay.h), or an empty one when a check fails (every boundary
// edge of U an edge of the gaps' triangulation, bordered there by gap triangles on its far side
// only, 2 N - 2 - H triangles for H hull edges, gap triangles counter-clockwise by exact
// predicates, open edges only on the hull): the caller then triangulates from scratch. Not
// Delaunay in general: flip it (lawson_repair.h or the GPU engine's repair).
Triangulation complete_triangulation(const std::vector<Vec2>& points, Triangulation partial,
                                     int32_t always_gap);

}  // namespace meshd
