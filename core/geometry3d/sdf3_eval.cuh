// The one 3D signed-distance evaluator, compiled by g++ for the CPU engine and by nvcc for the
// GPU engine. Every primitive's distance is exact (program3d.h: transforms are already folded
// into each primitive's frame); CSG combinations use min / max as DistMesh does (exact outside a
// union, a bound elsewhere). Negative inside, in the request's length unit.
//
// Each q below points at the primitive's parameters in the layout program3d.h documents.
#pragma once

#include <cmath>

#include "core/common/hd.h"
#include "core/common/vec3.h"
#include "core/geometry/sdf_eval.cuh"
#include "core/geometry3d/program3d.h"
#include "core/geometry3d/surface_sdf3.cuh"

namespace meshd {
namespace sdf3_detail {

// Plain sqrt rather than hypot: libm's hypot guards against overflow that lengths in a mesh
// never reach, and costs several times more on the hot path.
MESHD_HD inline double length2(double x, double y) { return sqrt(x * x + y * y); }
MESHD_HD inline double length3(double x, double y, double z) { return sqrt(x * x + y * y + z * z); }
MESHD_HD inline double maxd(double a, double b) { return a > b ? a : b; }
MESHD_HD inline double mind(double a, double b) { return a < b ? a : b; }
MESHD_HD inline Vec3 load3(const double* q) { return {q[0], q[1], q[2]}; }

// Where p lies relative to an axis through c with unit direction a: `axial` along it, `radial`
// away from it (>= 0). The radial part is the length of the perpendicular vector itself, not
// sqrt(|d|^2 - axial^2), which would lose every digit near the axis.
struct AxialCoords {
  double axial;
  double radial;
};
MESHD_HD inline AxialCoords axial_coords(const double* c, const double* a, Vec3 p) {
  const Vec3 d = p - load3(c), axis = load3(a);
  const double z = dot(d, axis);
  return {z, norm(d - z * axis)};
}

// Distance from (x, y) to the segment from (ax, ay) to (bx, by) of non-zero length.
MESHD_HD inline double segment_distance2(double x, double y, double ax, double ay, double bx,
                                         double by) {
  const double ex = bx - ax, ey = by - ay, px = x - ax, py = y - ay;
  double t = (px * ex + py * ey) / (ex * ex + ey * ey);
  t = t < 0.0 ? 0.0 : (t > 1.0 ? 1.0 : t);
  return length2(px - t * ex, py - t * ey);
}

// The exact signed distance of the 2D box |x| <= hx, |y| <= hy, rounded outside its corners.
MESHD_HD inline double box2(double x, double y, double hx, double hy) {
  const double lx = fabs(x) - hx, ly = fabs(y) - hy;
  return length2(maxd(lx, 0.0), maxd(ly, 0.0)) + mind(maxd(lx, ly), 0.0);
}

}  // namespace sdf3_detail

MESHD_HD inline double sdf3_sphere(const double* q, Vec3 p) {
  return sdf3_detail::length3(p.x - q[0], p.y - q[1], p.z - q[2]) - q[3];
}

// Exact, with the rounded distance field outside its edges and corners.
MESHD_HD inline double sdf3_cuboid(const double* q, Vec3 p) {
  using namespace sdf3_detail;
  const Vec3 d = p - load3(q);
  const double lx = fabs(dot(load3(q + 3), d)) - q[12];
  const double ly = fabs(dot(load3(q + 6), d)) - q[13];
  const double lz = fabs(dot(load3(q + 9), d)) - q[14];
  return length3(maxd(lx, 0.0), maxd(ly, 0.0), maxd(lz, 0.0)) + mind(maxd(lx, maxd(ly, lz)), 0.0);
}

// A solid of revolution's distance is its profile's 2D distance in the (radial, axial)
// half-plane through p: the nearest boundary point lies in that half-plane. For the capped
// cylinder the profile, mirrored about the axis, is a box.
MESHD_HD inline double sdf3_cylinder(const double* q, Vec3 p) {
  const sdf3_detail::AxialCoords c = sdf3_detail::axial_coords(q, q + 3, p);
  return sdf3_detail::box2(c.radial, c.axial, q[6], q[7]);
}

// The profile is the trapezoid (0, 0), (rb, 0), (rt, h), (0, h); its side on the axis is no
// boundary, so the distance is the nearest of the bottom, the slanted side and the top. A zero
// radius shrinks its cap to the apex, an end of the slanted side, so the apex needs no case.
MESHD_HD inline double sdf3_frustum(const double* q, Vec3 p) {
  using namespace sdf3_detail;
  const AxialCoords c = axial_coords(q, q + 3, p);
  const double rb = q[6], rt = q[7], h = q[8];
  const double z = c.axial, r = c.radial;
  const double bottom = length2(maxd(r - rb, 0.0), z);
  const double top = length2(maxd(r - rt, 0.0), z - h);
  const double side = segment_distance2(r, z, rb, 0.0, rt, h);
  const double d = mind(side, mind(bottom, top));
  const bool inside = z >= 0.0 && z <= h && r * h <= rb * h + (rt - rb) * z;
  return inside ? -d : d;
}

MESHD_HD inline double sdf3_torus(const double* q, Vec3 p) {
  const sdf3_detail::AxialCoords c = sdf3_detail::axial_coords(q, q + 3, p);
  return sdf3_detail::length2(c.radial - q[6], c.axial) - q[7];
}

MESHD_HD inline double sdf3_half_space(const double* q, Vec3 p) {
  return q[0] * p.x + q[1] * p.y + q[2] * p.z - q[3];
}

// A profile's distance d2 and the slab's dz combined as a box's faces are: exact outside where
// both are, and the larger inside.
MESHD_HD inline double sdf3_extrusion(const double* q, const ProgramView* profiles, Vec3 p) {
  using namespace sdf3_detail;
  const Vec3 d = p - load3(q);
  const double s = q[12], h = q[13];
  const double x = dot(d, load3(q + 3)) / s, y = dot(d, load3(q + 6)) / s;
  const double z = dot(d, load3(q + 9)) / s;
  const double d2 = eval_sdf(profiles[static_cast<int>(q[18])], Vec2{x, y});
  const double dz = fabs(z - 0.5 * h) - 0.5 * h;
  return s * (length2(maxd(d2, 0.0), maxd(dz, 0.0)) + mind(maxd(d2, dz), 0.0));
}

// The profile's distance at (distance from the axis, height along it).
MESHD_HD inline double sdf3_revolution(const double* q, const ProgramView* profiles, Vec3 p) {
  const sdf3_detail::AxialCoords a = sdf3_detail::axial_coords(q, q + 3, p);
  const double s = q[6];
  return s * eval_sdf(profiles[static_cast<int>(q[10])], Vec2{a.radial / s, a.axial / s});
}

// cap: the distance a polyhedron need not know beyond (sdf3_surface).
MESHD_HD inline double sdf3_primitive(Program3View prog, const Instruction3& ins, Vec3 p,
                                      double cap) {
  const double* q = prog.params + ins.operand;
  switch (ins.op) {
    case Op3::kSphere:
      return sdf3_sphere(q, p);
    case Op3::kCuboid:
      return sdf3_cuboid(q, p);
    case Op3::kCylinder:
      return sdf3_cylinder(q, p);
    case Op3::kFrustum:
      return sdf3_frustum(q, p);
    case Op3::kTorus:
      return sdf3_torus(q, p);
    case Op3::kHalfSpace:
      return sdf3_half_space(q, p);
    case Op3::kExtrusion:
      return sdf3_extrusion(q, prog.profiles, p);
    case Op3::kRevolution:
      return sdf3_revolution(q, prog.profiles, p);
    case Op3::kPolyhedron:
      return sdf3_surface(prog.surfaces[static_cast<int>(q[6])], p, cap);
    default:
      return NAN;
  }
}

// g++ cannot see that a compiled program always pushes before it pops, and where this inlines
// deep enough it warns that the stack may be read uninitialised. Initialising the stack would
// cost every evaluation a store on the GPU's hot path, so the warning is silenced here alone.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
// Signed distance of the whole program at p. When `owner` is not null it receives the index of
// the primitive whose distance the result is (the boundary it is nearest to), which tags
// boundary faces with their group. With a finite `cap` the result is exact where its magnitude
// is under cap, and at least cap (with the right sign) elsewhere: a polyhedron then answers
// +-cap far from its surface, and clamping commutes with min, max and negation.
MESHD_HD inline double eval_sdf3(Program3View prog, Vec3 p, int* owner = nullptr,
                                 double cap = INFINITY) {
  double value[kMaxProgram3Stack];
  int who[kMaxProgram3Stack];
  int top = -1;
  for (uint32_t i = 0; i < prog.size; ++i) {
    const Instruction3 ins = prog.code[i];
    switch (ins.op) {
      case Op3::kMin:
        --top;
        if (value[top + 1] < value[top]) {
          value[top] = value[top + 1];
          who[top] = who[top + 1];
        }
        break;
      case Op3::kMax:
        --top;
        if (value[top + 1] > value[top]) {
          value[top] = value[top + 1];
          who[top] = who[top + 1];
        }
        break;
      case Op3::kNegate:
        value[top] = -value[top];
        break;
      default:
        ++top;
        value[top] = sdf3_primitive(prog, ins, p, cap);
        who[top] = ins.primitive;
        break;
    }
  }
  if (owner != nullptr) *owner = who[0];
  return value[0];
}
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif

}  // namespace meshd
