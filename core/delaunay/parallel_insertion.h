// Delaunay triangulation by parallel point insertion (parallel_insertion.cuh), run on the host:
// the reference that the device's builder (kernels/point_insertion.h) is held to, and the same
// steps in the same order. CGAL's delaunay_triangulate stays the CPU engine's builder.
#pragma once

#include <cstdint>
#include <vector>

#include "core/common/vec2.h"
#include "core/delaunay/delaunay.h"

namespace meshd {

struct InsertionStats {
  int insertion_steps = 0;
  int flip_steps = 0;
  int64_t flips = 0;  // by the insertion's certain tests
  int64_t duplicates = 0;
  bool fell_back = false;  // the completion's checks failed: CGAL from scratch instead
};

// The indices of the points that are kept, increasing: the first of each set of equal points.
std::vector<int32_t> distinct_points(const std::vector<Vec2>& points);

// Delaunay triangulation of `points` as delaunay.h returns it (duplicates left out), built by
// the insertion's steps on the host, then completed to the convex hull and flipped with exact
// predicates.
Triangulation insertion_triangulate(const std::vector<Vec2>& points,
                                    InsertionStats* stats = nullptr);

}  // namespace meshd
