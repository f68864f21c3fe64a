// The numerical gradient of a 3D domain's distance and the projection onto its boundary (step 8
// of the 3D loop), shared by the step and the sliver optimisation.
#pragma once

#include "core/common/vec3.h"
#include "core/distmesh3d/domain3d.h"

namespace meshd {

// Forward-difference gradient of the distance at p, where it is d; step > 0 absolute
// (distmeshnd's deps h0).
inline Vec3 distance_gradient3d(const Domain3& domain, Vec3 p, double d, double step) {
  return {(domain.distance({p.x + step, p.y, p.z}) - d) / step,
          (domain.distance({p.x, p.y + step, p.z}) - d) / step,
          (domain.distance({p.x, p.y, p.z + step}) - d) / step};
}

// One Newton step towards the zero level set: p - d grad / |grad|^2, with distance d at p.
inline Vec3 project_step3d(const Domain3& domain, Vec3 p, double d, double step) {
  const Vec3 g = distance_gradient3d(domain, p, d, step);
  const double g2 = dot(g, g);
  return g2 > 0.0 ? p - (d / g2) * g : p;
}

// Moves p onto the boundary (from either side) with a few Newton steps.
inline Vec3 project_to_boundary3d(const Domain3& domain, Vec3 p, double step, int steps = 3) {
  for (int i = 0; i < steps; ++i) p = project_step3d(domain, p, domain.distance(p), step);
  return p;
}

}  // namespace meshd
