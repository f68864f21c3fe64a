// The quality of one tetrahedron, shared by the host and (later) the device: the radius ratio
// q = 3 r_in / R_circ (simpqual.m's 3D measure; 1 for the regular tetrahedron, 0 for a flat
// one) and its six dihedral angles.
#pragma once

#include <cmath>

#include "core/common/hd.h"
#include "core/common/vec3.h"

namespace meshd {

// 1 / the largest coordinate difference of b, c, d from a (u, v, w = b - a, c - a, d - a), or 0
// when there is none or it is infinite. The measures below are free of scale and compute on the
// edges multiplied by it, so that the squares and fourth powers of lengths they form neither
// underflow nor overflow, whatever the length unit.
// Comparisons rather than fmax and fmin, which g++ leaves as library calls (for NaN's sake; a NaN
// coordinate gives q = 0 and zero angles all the same): the sliver removal measures millions of
// tetrahedra.
MESHD_HD inline double max_by_compare(double a, double b) { return a > b ? a : b; }
MESHD_HD inline double min_by_compare(double a, double b) { return a < b ? a : b; }

MESHD_HD inline double tet_unit_scale(Vec3 u, Vec3 v, Vec3 w) {
  const auto max_abs = [](Vec3 e) {
    return max_by_compare(fabs(e.x), max_by_compare(fabs(e.y), fabs(e.z)));
  };
  const double m = max_by_compare(max_abs(u), max_by_compare(max_abs(v), max_abs(w)));
  return m > 0.0 ? 1.0 / m : 0.0;
}

// q of the tetrahedron abcd, negative when it is negatively oriented (tet_mesh.h), 0 when it is
// flat or has coincident corners; |q| <= 1 up to rounding. With u, v, w the edges from a,
// 6V = u . (v x w) and S the four faces' area: r_in = 3 V / S, and the circumcentre is
// a + C / (2 6V) with C = u^2 (v x w) + v^2 (w x u) + w^2 (u x v) (the closed form of the 3 by 3
// system |x - a| = |x - b| = |x - c| = |x - d|, relative to a so that translation costs no
// digits), so R_circ = |C| / (12 V) and q = 6 (6V)^2 / (2S |C|). V enters squared in the
// numerator and |C| stays finite as V -> 0, so a flat tetrahedron has q = 0 without a division
// by its volume.
MESHD_HD inline double oriented_tet_radius_ratio(Vec3 a, Vec3 b, Vec3 c, Vec3 d) {
  const double s = tet_unit_scale(b - a, c - a, d - a);
  const Vec3 u = s * (b - a), v = s * (c - a), w = s * (d - a);
  const double six_volume = dot(u, cross(v, w));
  const double twice_area =
      norm(cross(u, v)) + norm(cross(v, w)) + norm(cross(w, u)) + norm(cross(v - u, w - u));
  const Vec3 circum = dot(u, u) * cross(v, w) + dot(v, v) * cross(w, u) + dot(w, w) * cross(u, v);
  const double circum_norm = norm(circum);
  // Written so that NaN coordinates give 0 too.
  if (!(twice_area > 0.0) || !(circum_norm > 0.0)) return 0.0;
  return 6.0 * six_volume * fabs(six_volume) / (twice_area * circum_norm);
}

// The six dihedral angles of abcd in degrees, in [0, 180], one per edge in the order ab, ac, ad,
// bc, bd, cd: at each edge, the angle inside the tetrahedron between the two faces that meet
// there. They do not depend on the orientation. An edge of a face with zero area gets 0, so a
// tetrahedron with a collapsed face reports a zero smallest angle (all four corners equal: all
// six are 0).
MESHD_HD inline void tet_dihedral_angles(Vec3 a, Vec3 b, Vec3 c, Vec3 d, double angles_deg[6]) {
  // A local table rather than one at namespace scope: device code may not read host arrays.
  const int edges[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
  const double s = tet_unit_scale(b - a, c - a, d - a);
  const Vec3 p[4] = {{0.0, 0.0, 0.0}, s * (b - a), s * (c - a), s * (d - a)};
  // n[k]: the normal of the face opposite corner k, turned away from that corner (outward for a
  // positive tetrahedron, inward for a negative one: the same for every face, so the angles
  // between them do not change).
  Vec3 n[4];
  for (int k = 0; k < 4; ++k) {
    const Vec3 q0 = p[(k + 1) % 4], q1 = p[(k + 2) % 4], q2 = p[(k + 3) % 4];
    const Vec3 m = cross(q1 - q0, q2 - q0);
    n[k] = dot(m, p[k] - q0) > 0.0 ? -1.0 * m : m;
  }
  for (int e = 0; e < 6; ++e) {
    // The faces that meet at edge (i, j) are those opposite the other two corners.
    const int i = edges[e][0], j = edges[e][1];
    const int k = (i != 0 && j != 0) ? 0 : (i != 1 && j != 1) ? 1 : (i != 2 && j != 2) ? 2 : 3;
    const int l = 6 - i - j - k;
    const Vec3 nk = n[k], nl = n[l];
    if (!(dot(nk, nk) > 0.0) || !(dot(nl, nl) > 0.0)) {
      angles_deg[e] = 0.0;
      continue;
    }
    // The inside angle is 180 degrees less the angle between the outward normals; atan2 keeps
    // its digits near 0 and 180, where acos of a cosine loses them.
    const double between = atan2(norm(cross(nk, nl)), dot(nk, nl));
    angles_deg[e] = 180.0 - between * (180.0 / M_PI);
  }
}

// The smallest and largest of the six dihedral angles of abcd, in degrees.
MESHD_HD inline void tet_dihedral_range(Vec3 a, Vec3 b, Vec3 c, Vec3 d, double& min_deg,
                                        double& max_deg) {
  double angles[6];
  tet_dihedral_angles(a, b, c, d, angles);
  min_deg = angles[0];
  max_deg = angles[0];
  for (int e = 1; e < 6; ++e) {
    min_deg = min_by_compare(min_deg, angles[e]);
    max_deg = max_by_compare(max_deg, angles[e]);
  }
}

}  // namespace meshd
