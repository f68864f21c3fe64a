// The numerical gradient of the distance and the projection onto the boundary (DistMesh step 7),
// shared by the engines and the clean-up.
#pragma once

#include "core/geometry/sdf_eval.cuh"

namespace meshd {

// Forward-difference gradient of fd at p, where fd(p) = d; step deps (absolute). `nested` as in
// eval_sdf.
MESHD_HD inline Vec2 sdf_gradient(ProgramView fd, Vec2 p, double d, double deps,
                                  bool nested = false) {
  return {(eval_sdf(fd, {p.x + deps, p.y}, nested) - d) / deps,
          (eval_sdf(fd, {p.x, p.y + deps}, nested) - d) / deps};
}

// One Newton step towards the zero level set: p - d grad / |grad|^2, with fd(p) = d.
MESHD_HD inline Vec2 project_step(ProgramView fd, Vec2 p, double d, double deps,
                                  bool nested = false) {
  const Vec2 g = sdf_gradient(fd, p, d, deps, nested);
  const double g2 = dot(g, g);
  return g2 > 0.0 ? p - (d / g2) * g : p;
}

// Moves p onto the boundary (from either side) with a few Newton steps.
MESHD_HD inline Vec2 project_to_boundary(ProgramView fd, Vec2 p, double deps, int steps = 3) {
  for (int i = 0; i < steps; ++i) p = project_step(fd, p, eval_sdf(fd, p), deps);
  return p;
}

}  // namespace meshd
