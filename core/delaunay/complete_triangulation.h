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
#include <utility>
#include <vector>

#include "core/common/vec2.h"
#include "core/delaunay/delaunay.h"

namespace meshd {

// Retries of a completion after a failed check, each without the triangles next to a gap.
constexpr int kMaxCompletionErosions = 4;

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

// The same in parts, for an engine that keeps U elsewhere (the GPU engine keeps it on the
// device and sends the host only what bounds the gaps).
//
// What bounds U's gaps: their points (on U's boundary, in no triangle of U, or among the first
// always_gap), in increasing order, with their positions; U's boundary edges (walls) directed
// with U on their left, each with its use 3 t + k in U (triangle t's neighbour slot k).
struct GapBoundary {
  std::vector<int32_t> points;
  std::vector<Vec2> positions;
  std::vector<std::array<int32_t, 2>> walls;
  std::vector<int64_t> wall_uses;
};
// The gaps' triangles (point indices of all N), numbered u_count on, with their neighbours (gap
// triangles, U's triangles across walls, -1 on the hull), and for each wall off the hull the
// gap triangle across it: (its use in U, that triangle).
struct GapFill {
  std::vector<std::array<int32_t, 3>> triangles, neighbors;
  std::vector<std::pair<int64_t, int32_t>> wall_links;
};
// Triangulates the gaps of a partial triangulation U of `n` points with `u_count` triangles
// from what bounds them. Returns false when a check of complete_triangulation fails: then the
// caller erodes U (drops its triangles with an open edge) and tries again, or gives up.
bool fill_gaps(const GapBoundary& boundary, int64_t n, int64_t u_count, GapFill& fill);

}  // namespace meshd
