// Orientation and in-sphere tests in space with Shewchuk's static error bounds (stage A of his
// adaptive predicates), on the host and the device: +1 or -1 when the bound makes the sign
// certain, 0 when it cannot decide. The device's flip repair (kernels/flip_repair3.h) acts only
// on certain answers; exact_predicates.h has the exact ones the tests hold these to. nvcc compiles
// the kernels without fused multiply-adds (kernels/CMakeLists.txt), which the bounds assume.
#pragma once

#include <cmath>

#include "core/common/hd.h"
#include "core/common/vec3.h"

namespace meshd {

// +1 when (b - a) . ((c - a) x (d - a)) > 0 for certain (delaunay3d.h's positive orientation),
// -1 when certainly < 0.
MESHD_HD inline int orientation3_filtered(Vec3 a, Vec3 b, Vec3 c, Vec3 d) {
  constexpr double kEps = 1.1102230246251565e-16;  // 2^-53
  constexpr double kBound = (7.0 + 56.0 * kEps) * kEps;
  const double adx = a.x - d.x, bdx = b.x - d.x, cdx = c.x - d.x;
  const double ady = a.y - d.y, bdy = b.y - d.y, cdy = c.y - d.y;
  const double adz = a.z - d.z, bdz = b.z - d.z, cdz = c.z - d.z;
  const double bdxcdy = bdx * cdy, cdxbdy = cdx * bdy;
  const double cdxady = cdx * ady, adxcdy = adx * cdy;
  const double adxbdy = adx * bdy, bdxady = bdx * ady;
  // Shewchuk's orient3d, whose sign is the opposite of this convention's.
  const double det = adz * (bdxcdy - cdxbdy) + bdz * (cdxady - adxcdy) + cdz * (adxbdy - bdxady);
  const double permanent = (fabs(bdxcdy) + fabs(cdxbdy)) * fabs(adz) +
                           (fabs(cdxady) + fabs(adxcdy)) * fabs(bdz) +
                           (fabs(adxbdy) + fabs(bdxady)) * fabs(cdz);
  const double bound = kBound * permanent;
  if (det < -bound) return 1;
  if (det > bound) return -1;
  return 0;
}

// +1 when e lies certainly inside the sphere through the positively oriented a, b, c, d, -1
// certainly outside.
MESHD_HD inline int in_sphere_filtered(Vec3 a, Vec3 b, Vec3 c, Vec3 d, Vec3 e) {
  constexpr double kEps = 1.1102230246251565e-16;
  constexpr double kBound = (16.0 + 224.0 * kEps) * kEps;
  const double aex = a.x - e.x, bex = b.x - e.x, cex = c.x - e.x, dex = d.x - e.x;
  const double aey = a.y - e.y, bey = b.y - e.y, cey = c.y - e.y, dey = d.y - e.y;
  const double aez = a.z - e.z, bez = b.z - e.z, cez = c.z - e.z, dez = d.z - e.z;
  const double aexbey = aex * bey, bexaey = bex * aey;
  const double bexcey = bex * cey, cexbey = cex * bey;
  const double cexdey = cex * dey, dexcey = dex * cey;
  const double dexaey = dex * aey, aexdey = aex * dey;
  const double aexcey = aex * cey, cexaey = cex * aey;
  const double bexdey = bex * dey, dexbey = dex * bey;
  const double ab = aexbey - bexaey, bc = bexcey - cexbey, cd = cexdey - dexcey;
  const double da = dexaey - aexdey, ac = aexcey - cexaey, bd = bexdey - dexbey;
  const double abc = aez * bc - bez * ac + cez * ab;
  const double bcd = bez * cd - cez * bd + dez * bc;
  const double cda = cez * da + dez * ac + aez * cd;
  const double dab = dez * ab + aez * bd + bez * da;
  const double alift = aex * aex + aey * aey + aez * aez;
  const double blift = bex * bex + bey * bey + bez * bez;
  const double clift = cex * cex + cey * cey + cez * cez;
  const double dlift = dex * dex + dey * dey + dez * dez;
  // Shewchuk's insphere: positive inside for his positive orientation, which is this one's
  // negative.
  const double det = (dlift * abc - clift * dab) + (blift * cda - alift * bcd);
  const double aezp = fabs(aez), bezp = fabs(bez), cezp = fabs(cez), dezp = fabs(dez);
  const double abp = fabs(aexbey) + fabs(bexaey), bcp = fabs(bexcey) + fabs(cexbey);
  const double cdp = fabs(cexdey) + fabs(dexcey), dap = fabs(dexaey) + fabs(aexdey);
  const double acp = fabs(aexcey) + fabs(cexaey), bdp = fabs(bexdey) + fabs(dexbey);
  const double permanent = (cdp * bezp + bdp * cezp + bcp * dezp) * alift +
                           (dap * cezp + acp * dezp + cdp * aezp) * blift +
                           (abp * dezp + bdp * aezp + dap * bezp) * clift +
                           (bcp * aezp + acp * bezp + abp * cezp) * dlift;
  const double bound = kBound * permanent;
  if (det < -bound) return 1;
  if (det > bound) return -1;
  return 0;
}

}  // namespace meshd
