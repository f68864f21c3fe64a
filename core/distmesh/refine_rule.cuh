// The rules of midpoint refinement (refine.h) that both engines apply: which edges split, where
// their midpoints go, and how a triangle splits over them. g++ and nvcc compile the same text, so
// a level refined on the device has the bits of one refined on the host.
#pragma once

#include <cstdint>

#include "core/common/hd.h"
#include "core/common/vec2.h"
#include "core/geometry/projection.cuh"
#include "core/geometry/size_eval.cuh"

namespace meshd {

// An edge is split when it is longer than this many times the finer level's edge at its midpoint
// (h0 h): halving it then brings it nearer that length, in ratio, than keeping it.
constexpr double kSplitAbove = 1.4142135623730951;  // sqrt(2)

// Whether edge (a, b) of a coarse level splits for the finer level's `h0`; if so, `mid` is its
// midpoint, projected onto the boundary (step deps) where the edge bounds the mesh.
MESHD_HD inline bool split_point(ProgramView fd, SizeView fh, double h0, double deps, Vec2 a,
                                 Vec2 b, bool bounds_mesh, Vec2& mid) {
  mid = 0.5 * (a + b);
  if (!(norm(b - a) > kSplitAbove * h0 * eval_size(fh, mid))) return false;
  if (bounds_mesh) mid = project_to_boundary(fd, mid, deps);
  return true;
}

// The triangles that cover triangle t = (a, b, c) once the edges with a midpoint (m[k] >= 0 for
// edge k, from corner k to corner k + 1) are split, in the parent's orientation: 1 to 4 of them
// in out, their count returned. `points` holds the corners and the midpoints.
MESHD_HD inline int split_triangle(const Vec2* points, const int32_t t[3], const int32_t m[3],
                                   int32_t out[4][3]) {
  auto put = [&](int i, int32_t x, int32_t y, int32_t z) {
    out[i][0] = x;
    out[i][1] = y;
    out[i][2] = z;
  };
  const int splits = (m[0] >= 0) + (m[1] >= 0) + (m[2] >= 0);
  if (splits == 0) {
    put(0, t[0], t[1], t[2]);
    return 1;
  }
  if (splits == 3) {
    put(0, t[0], m[0], m[2]);
    put(1, m[0], t[1], m[1]);
    put(2, m[2], m[1], t[2]);
    put(3, m[0], m[1], m[2]);
    return 4;
  }
  // Turn the corners so that edge 0 is split and, with two splits, edge 1 too.
  const int first = splits == 1 ? (m[0] >= 0   ? 0
                                   : m[1] >= 0 ? 1
                                               : 2)
                                : (m[0] < 0   ? 1
                                   : m[1] < 0 ? 2
                                              : 0);
  const int32_t a = t[first], b = t[(first + 1) % 3], c = t[(first + 2) % 3];
  const int32_t m0 = m[first], m1 = m[(first + 1) % 3];
  if (splits == 1) {
    put(0, a, m0, c);
    put(1, m0, b, c);
    return 2;
  }
  // Corner b is cut off; the quadrilateral a, m0, m1, c left takes its shorter diagonal.
  put(0, m0, b, m1);
  const double via_a = norm(points[m1] - points[a]), via_c = norm(points[m0] - points[c]);
  if (via_a <= via_c) {
    put(1, a, m0, m1);
    put(2, a, m1, c);
  } else {
    put(1, a, m0, c);
    put(2, m0, m1, c);
  }
  return 3;
}

}  // namespace meshd
