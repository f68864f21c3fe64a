// Signed distance to a polygon (parameters `n x0 y0 ... x(n-1) y(n-1) s`, program.h), by
// visiting every edge or, for a polygon of many vertices, only the edges its tree (bvh.h)
// brings near. Both give bit for bit the same distance: the same per-edge formula, and a
// minimum. The plain walk signs it by the even-odd crossing number of a horizontal ray. The
// indexed one cannot afford a ray through a long polygon, and signs it by the nearest feature
// instead: the side of the nearest edge's line, or, where the nearest point is a vertex, the
// side of the sum of its two edges' unit normals (a pseudo-normal, which tells a convex vertex
// from a reflex one without a threshold). For a simple polygon both signs agree wherever the
// distance is not 0; s (+1 counter-clockwise, -1 clockwise) says which side is outside.
#pragma once

#include <cmath>
#include <cstdint>

#include "core/common/hd.h"
#include "core/common/vec2.h"
#include "core/geometry/bvh.h"

namespace meshd {

MESHD_HD inline Vec2 polygon_vertex(const double* v, int n, int i) {
  const int k = i < 0 ? i + n : (i >= n ? i - n : i);
  return {v[2 * k], v[2 * k + 1]};
}

// Squared distance from p to edge i (vertex i to vertex i + 1, cyclically); `t` receives the
// parameter of the nearest point along the edge, in [0, 1].
MESHD_HD inline double polygon_edge_distance2(const double* v, int n, int i, Vec2 p, double& t) {
  const Vec2 a = polygon_vertex(v, n, i), b = polygon_vertex(v, n, i + 1);
  const Vec2 e = b - a, w = p - a;
  const double ee = dot(e, e);
  // Comparisons rather than fmin / fmax, which g++ leaves as library calls (for NaN's sake).
  const double u = ee > 0.0 ? dot(w, e) / ee : 0.0;
  t = u < 0.0 ? 0.0 : (u > 1.0 ? 1.0 : u);
  const Vec2 r = w - t * e;
  return dot(r, r);
}

// Outward unit normal of edge i of a counter-clockwise polygon.
MESHD_HD inline Vec2 polygon_edge_normal(const double* v, int n, int i) {
  const Vec2 e = polygon_vertex(v, n, i + 1) - polygon_vertex(v, n, i);
  return (1.0 / norm(e)) * Vec2{e.y, -e.x};
}

// Whether edge i crosses the horizontal ray from p toward +x.
MESHD_HD inline bool polygon_edge_crosses(const double* v, int n, int i, Vec2 p) {
  const Vec2 a = polygon_vertex(v, n, i), b = polygon_vertex(v, n, i + 1);
  if ((a.y > p.y) == (b.y > p.y)) return false;
  return p.x < a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y);
}

MESHD_HD inline double sdf_polygon(const double* q, Vec2 p) {
  const int n = static_cast<int>(q[0]);
  const double* v = q + 1;
  double best = INFINITY;
  bool inside = false;
  for (int i = 0; i < n; ++i) {
    double t;
    const double d2 = polygon_edge_distance2(v, n, i, p, t);
    if (d2 < best) best = d2;
    if (polygon_edge_crosses(v, n, i, p)) inside = !inside;
  }
  const double d = sqrt(best);
  return inside ? -d : d;
}

// The same through the tree rooted at nodes[root], whose leaves are runs of edges.
MESHD_HD inline double sdf_polygon_indexed(const double* q, const BvhNode* nodes, uint32_t root,
                                           Vec2 p) {
  const int n = static_cast<int>(q[0]);
  const double* v = q + 1;
  // Nearest edge: nearer child first, and no box farther than the best edge so far.
  uint32_t stack[kMaxBvhDepth + 2];
  double best = INFINITY, best_t = 0.0;
  int best_edge = 0;
  int top = 0;
  stack[0] = root;
  while (top >= 0) {
    const BvhNode& node = nodes[stack[top--]];
    if (box_distance2(node.box, p) >= best) continue;
    if (node.leaf) {
      for (uint32_t i = node.first; i < node.last; ++i) {
        double t;
        const double d2 = polygon_edge_distance2(v, n, static_cast<int>(i), p, t);
        if (d2 < best) {
          best = d2;
          best_t = t;
          best_edge = static_cast<int>(i);
        }
      }
      continue;
    }
    const double dl = box_distance2(nodes[node.first].box, p);
    const double dr = box_distance2(nodes[node.last].box, p);
    const bool left_first = dl <= dr;
    if ((left_first ? dr : dl) < best) stack[++top] = left_first ? node.last : node.first;
    if ((left_first ? dl : dr) < best) stack[++top] = left_first ? node.first : node.last;
  }
  // The side of the nearest feature, with normals turned outward by the orientation s.
  const double s = q[1 + 2 * n];
  double side;
  if (best_t > 0.0 && best_t < 1.0) {
    side = dot(p - polygon_vertex(v, n, best_edge), polygon_edge_normal(v, n, best_edge));
  } else {
    const int k = best_t > 0.0 ? best_edge + 1 : best_edge;  // the vertex
    side = dot(p - polygon_vertex(v, n, k),
               polygon_edge_normal(v, n, k - 1) + polygon_edge_normal(v, n, k));
  }
  const double d = sqrt(best);
  return s * side < 0.0 ? -d : d;
}

}  // namespace meshd
