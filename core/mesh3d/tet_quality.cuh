// The quality of one tetrahedron, shared by the host and (later) the device: the radius ratio
// q = 3 r_in / R_circ (simpqual.m's 3D measure; 1 for the regular tetrahedron, 0 for a flat
// one) and its dihedral angles.
#pragma once

#include <cmath>

#include "core/common/hd.h"
#include "core/common/vec3.h"

namespace meshd {

// q of the tetrahedron abcd, negative when it is negatively oriented, 0 when it is flat. With
// u, v, w the edges from a, 6V = u . (v x w) and S the four faces' area: r_in = 3 V / S and
// R_circ = |u^2 (v x w) + v^2 (w x u) + w^2 (u x v)| / (12 V), so q = 6 (6V)^2 / (2S |...|).
MESHD_HD inline double oriented_tet_radius_ratio(Vec3 a, Vec3 b, Vec3 c, Vec3 d) {
  const Vec3 u = b - a, v = c - a, w = d - a;
  const double six_volume = dot(u, cross(v, w));
  const double twice_area =
      norm(cross(u, v)) + norm(cross(v, w)) + norm(cross(w, u)) + norm(cross(c - b, d - b));
  const Vec3 circum = dot(u, u) * cross(v, w) + dot(v, v) * cross(w, u) + dot(w, w) * cross(u, v);
  const double circum_norm = norm(circum);
  if (!(twice_area > 0.0) || !(circum_norm > 0.0)) return 0.0;
  return 6.0 * six_volume * std::fabs(six_volume) / (twice_area * circum_norm);
}

// The smallest and largest of the six dihedral angles of abcd, in degrees: at each edge, the
// angle between the two faces that meet there, measured inside.
MESHD_HD inline void tet_dihedral_range(Vec3 a, Vec3 b, Vec3 c, Vec3 d, double& min_deg,
                                        double& max_deg) {
  const Vec3 p[4] = {a, b, c, d};
  // Face k is opposite vertex k; its outward normal is n[k] (unnormalised).
  Vec3 n[4];
  for (int k = 0; k < 4; ++k) {
    const Vec3 q0 = p[(k + 1) % 4], q1 = p[(k + 2) % 4], q2 = p[(k + 3) % 4];
    Vec3 m = cross(q1 - q0, q2 - q0);
    if (dot(m, p[k] - q0) > 0.0) m = -1.0 * m;  // away from the opposite vertex
    n[k] = m;
  }
  min_deg = 180.0;
  max_deg = 0.0;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) {
      const double ni = norm(n[i]), nj = norm(n[j]);
      double angle = 0.0;  // a flat face: count its edges' angles as 0
      if (ni > 0.0 && nj > 0.0) {
        const double cosine = fmin(1.0, fmax(-1.0, dot(n[i], n[j]) / (ni * nj)));
        angle = 180.0 - acos(cosine) * (180.0 / M_PI);  // the inside angle between outward normals
      }
      min_deg = fmin(min_deg, angle);
      max_deg = fmax(max_deg, angle);
    }
}

}  // namespace meshd
