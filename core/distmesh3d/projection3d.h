// The numerical gradient of a 3D domain's distance and the projection onto its boundary (step 8
// of the 3D loop), shared by the step and the sliver optimisation.
#pragma once

#include <cmath>

#include "core/common/vec3.h"
#include "core/distmesh3d/domain3d.h"
#include "core/geometry3d/gradient3.cuh"

namespace meshd {

// Forward-difference gradient of the distance at p, where it is d; step > 0 absolute
// (distmeshnd's deps h0).
inline Vec3 distance_gradient3d(const Domain3& domain, Vec3 p, double d, double step) {
  return distance_gradient3(domain.distance, p, d, step);
}

// One Newton step towards the zero level set: p - d grad / |grad|^2, with distance d at p.
inline Vec3 project_step3d(const Domain3& domain, Vec3 p, double d, double step) {
  return project_step3(domain.distance, p, d, step);
}

// Eight unit directions in the boundary's tangent plane at p (about the distance's gradient),
// into dirs; returns 8, or 0 where the gradient vanishes.
inline int boundary_tangents3d(const Domain3& domain, Vec3 p, double step, Vec3* dirs) {
  const Vec3 g = distance_gradient3d(domain, p, domain.distance(p), step);
  const double len = norm(g);
  if (!(len > 0.0)) return 0;
  const Vec3 n = (1.0 / len) * g;
  // Any vector not along n, crossed with n, gives the first tangent.
  const Vec3 a = std::fabs(n.x) < 0.9 ? Vec3{1.0, 0.0, 0.0} : Vec3{0.0, 1.0, 0.0};
  Vec3 t1 = cross(n, a);
  t1 = (1.0 / norm(t1)) * t1;
  const Vec3 t2 = cross(n, t1);
  for (int k = 0; k < 8; ++k) dirs[k] = std::cos(k * M_PI / 4) * t1 + std::sin(k * M_PI / 4) * t2;
  return 8;
}

// Moves p onto the boundary (from either side) by Newton steps, until its distance is within a
// thousandth of `step` or after `steps`. A smooth surface takes one or two; a crease where CSG
// meets two surfaces at a slant takes more, each step landing on one surface a little outside the
// other.
inline Vec3 project_to_boundary3d(const Domain3& domain, Vec3 p, double step, int steps = 12) {
  for (int i = 0; i < steps; ++i) {
    const double d = domain.distance(p);
    if (std::fabs(d) <= 1e-3 * step) break;
    p = project_step3d(domain, p, d, step);
  }
  return p;
}

}  // namespace meshd
