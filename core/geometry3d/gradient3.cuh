// The numerical gradient of a 3D signed distance and one Newton step onto its zero level set,
// over any callable distance: the CPU engine's Domain3 and the GPU's compiled program alike, so
// that both project with the same arithmetic.
#pragma once

#include "core/common/hd.h"
#include "core/common/vec3.h"

namespace meshd {

// Forward-difference gradient of `distance` at p, where it is d; step > 0 absolute
// (distmeshnd's deps h0).
template <typename Distance>
MESHD_HD inline Vec3 distance_gradient3(const Distance& distance, Vec3 p, double d, double step) {
  return {(distance(Vec3{p.x + step, p.y, p.z}) - d) / step,
          (distance(Vec3{p.x, p.y + step, p.z}) - d) / step,
          (distance(Vec3{p.x, p.y, p.z + step}) - d) / step};
}

// One Newton step towards the zero level set: p - d grad / |grad|^2, with distance d at p.
template <typename Distance>
MESHD_HD inline Vec3 project_step3(const Distance& distance, Vec3 p, double d, double step) {
  const Vec3 g = distance_gradient3(distance, p, d, step);
  const double g2 = dot(g, g);
  return g2 > 0.0 ? p - (d / g2) * g : p;
}

}  // namespace meshd
