// The signed distance of a closed triangle surface (triangle_surface3.h), for the one 3D
// evaluator on the host and the device: the nearest triangle through the hierarchy, the sign from
// the pseudonormal of the face, edge or vertex its nearest point lies on.
#pragma once

#include <cmath>

#include "core/common/hd.h"
#include "core/common/vec3.h"
#include "core/geometry3d/triangle_surface3.h"

namespace meshd {
namespace surface_detail {

// Squared distance from p to the box (0 inside it).
MESHD_HD inline double box_distance2(const Box3& b, Vec3 p) {
  const double dx = p.x < b.min.x ? b.min.x - p.x : (p.x > b.max.x ? p.x - b.max.x : 0.0);
  const double dy = p.y < b.min.y ? b.min.y - p.y : (p.y > b.max.y ? p.y - b.max.y : 0.0);
  const double dz = p.z < b.min.z ? b.min.z - p.z : (p.z > b.max.z ? p.z - b.max.z : 0.0);
  return dx * dx + dy * dy + dz * dz;
}

struct Nearest {
  Vec3 point;
  int region;  // SurfaceRegion
};

// The point of triangle abc nearest to p and the region it lies in (Ericson, Real-Time Collision
// Detection, 5.1.5: p's projections onto the edges' lines decide the Voronoi region).
MESHD_HD inline Nearest nearest_on_triangle(Vec3 p, Vec3 a, Vec3 b, Vec3 c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0.0 && d2 <= 0.0) return {a, kOnA};
  const Vec3 bp = p - b;
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0.0 && d4 <= d3) return {b, kOnB};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return {a + (d1 / (d1 - d3)) * ab, kOnEdgeAB};
  const Vec3 cp = p - c;
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0.0 && d5 <= d6) return {c, kOnC};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return {a + (d2 / (d2 - d6)) * ac, kOnEdgeCA};
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0)
    return {b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b), kOnEdgeBC};
  const double denom = 1.0 / (va + vb + vc);
  return {a + (vb * denom) * ab + (vc * denom) * ac, kOnFace};
}

// Whether the ray from p along kRay crosses the triangle abc (Moller and Trumbore), at t > 0.
MESHD_HD inline bool ray_crosses(Vec3 p, Vec3 dir, Vec3 a, Vec3 b, Vec3 c) {
  const Vec3 e1 = b - a, e2 = c - a, h = cross(dir, e2);
  const double det = dot(e1, h);
  if (det == 0.0) return false;
  const double inv = 1.0 / det;
  const Vec3 s = p - a;
  const double u = dot(s, h) * inv;
  if (u < 0.0 || u > 1.0) return false;
  const Vec3 q = cross(s, e1);
  const double v = dot(dir, q) * inv;
  if (v < 0.0 || u + v > 1.0) return false;
  return dot(e2, q) * inv > 0.0;
}

// Whether the ray from p along dir (no zero component) meets the box.
MESHD_HD inline bool ray_meets_box(Vec3 p, Vec3 inv_dir, const Box3& b) {
  double t0 = 0.0, t1 = INFINITY;
  const double lo[3] = {b.min.x, b.min.y, b.min.z}, hi[3] = {b.max.x, b.max.y, b.max.z};
  const double o[3] = {p.x, p.y, p.z}, inv[3] = {inv_dir.x, inv_dir.y, inv_dir.z};
  for (int k = 0; k < 3; ++k) {
    double near = (lo[k] - o[k]) * inv[k], far = (hi[k] - o[k]) * inv[k];
    if (near > far) {
      const double t = near;
      near = far;
      far = t;
    }
    t0 = near > t0 ? near : t0;
    t1 = far < t1 ? far : t1;
    if (t0 > t1) return false;
  }
  return true;
}

// Inside by the parity of a ray's crossings: for points farther than any triangle worth finding,
// whose nearest triangle would cost a visit of most of them. The ray's direction leans on no
// axis and no simple lattice direction, so it meets an edge or a vertex of a modelled surface
// almost never (and such a point is far from the surface, where a miscounted sign only costs a
// node a projection).
MESHD_HD inline bool inside_by_ray(const TriangleSurface3View& s, Vec3 p) {
  const Vec3 dir{0.5773502691896258 + 0.0131, 0.5773502691896258 - 0.0217,
                 0.5773502691896258 + 0.0071};
  const Vec3 inv{1.0 / dir.x, 1.0 / dir.y, 1.0 / dir.z};
  uint32_t stack[kMaxSurfaceBvhDepth + 1];
  int top = 0;
  stack[0] = s.root;
  bool inside = false;
  while (top >= 0) {
    const SurfaceBvhNode& node = s.nodes[stack[top--]];
    if (!ray_meets_box(p, inv, node.box)) continue;
    if (!node.leaf) {
      stack[++top] = node.first;
      stack[++top] = node.last;
      continue;
    }
    for (uint32_t t = node.first; t < node.last; ++t) {
      const int32_t* v = s.triangles + 3 * t;
      if (ray_crosses(p, dir, s.vertices[v[0]], s.vertices[v[1]], s.vertices[v[2]]))
        inside = !inside;
    }
  }
  return inside;
}

}  // namespace surface_detail

// Signed distance from p to the surface, negative inside; where no triangle lies within `cap`,
// +-cap (the sign from a ray), which spares points deep inside a visit of most triangles (at a
// ball's centre all are equally far).
MESHD_HD inline double sdf3_surface(const TriangleSurface3View& s, Vec3 p, double cap = INFINITY) {
  using namespace surface_detail;
  uint32_t stack[kMaxSurfaceBvhDepth + 1];
  int top = 0;
  stack[0] = s.root;
  double best = cap * cap;
  Vec3 best_point{};
  Vec3 best_normal{};
  while (top >= 0) {
    const SurfaceBvhNode& node = s.nodes[stack[top--]];
    if (box_distance2(node.box, p) >= best) continue;
    if (!node.leaf) {
      // The nearer child last, so that it is visited first and prunes the other.
      const double dl = box_distance2(s.nodes[node.first].box, p);
      const double dr = box_distance2(s.nodes[node.last].box, p);
      stack[++top] = dl < dr ? node.last : node.first;
      stack[++top] = dl < dr ? node.first : node.last;
      continue;
    }
    for (uint32_t t = node.first; t < node.last; ++t) {
      const int32_t* v = s.triangles + 3 * t;
      const Nearest n =
          nearest_on_triangle(p, s.vertices[v[0]], s.vertices[v[1]], s.vertices[v[2]]);
      const Vec3 d = p - n.point;
      const double d2 = dot(d, d);
      if (d2 >= best) continue;
      best = d2;
      best_point = n.point;
      best_normal = n.region <= kOnEdgeCA ? s.triangle_normals[4 * t + n.region]
                                          : s.vertex_normals[v[n.region - kOnA]];
    }
  }
  if (!(best < cap * cap)) return inside_by_ray(s, p) ? -cap : cap;
  const double d = sqrt(best);
  return dot(p - best_point, best_normal) < 0.0 ? -d : d;
}

}  // namespace meshd
