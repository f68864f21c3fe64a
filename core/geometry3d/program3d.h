// The 3D geometry compiled to a flat postfix program, so that one small evaluator
// (sdf3_eval.cuh) computes the signed distance on the host and on the device alike.
//
// Invariants: `code` is postfix over a value stack. A primitive instruction pushes its distance;
// kMin and kMax pop two values and push one; kNegate flips the top. A well-formed program
// leaves exactly one value and never needs more than kMaxProgram3Stack slots (the compiler
// checks both).
//
// Transforms are similarities, and the compiler has already folded them into each primitive's
// own frame: a centre (or base point) in world coordinates, its unit axes in world coordinates
// (all three for a cuboid; the one symmetry axis for the solids of revolution) and its lengths
// multiplied by the accumulated scale. A rotation and a translation preserve distance, and the
// scale is already in the lengths, so every primitive's distance is exact in world units and
// evaluation needs no inverse transform.
//
// Parameter layout in `params`, starting at Instruction3::operand (all in world coordinates):
//   kSphere     cx cy cz r
//   kCuboid     cx cy cz ux uy uz vx vy vz wx wy wz hx hy hz
//               (centre; the cuboid's own x, y, z axes as unit vectors; half extents along them)
//   kCylinder   cx cy cz ax ay az r hh       (centre of the axis, unit axis, radius, half height)
//   kFrustum    bx by bz ax ay az rb rt h    (centre of the base, unit axis towards the top,
//                                             bottom and top radii, height)
//   kTorus      cx cy cz ax ay az R r        (centre, unit axis, major and minor radii)
//   kHalfSpace  nx ny nz c                   (unit normal; inside where n.p <= c)
//   kExtrusion  ox oy oz ux uy uz vx vy vz wx wy wz s h x0 y0 x1 y1 k
//               (the profile's origin; its x, y and extrusion axes as unit vectors; the scale;
//               the height and the profile's box in the profile's own units; its index k in
//               `profiles`)
//   kRevolution ox oy oz ax ay az s R z0 z1 k
//               (a point on the axis, the unit axis, the scale; the profile's largest x, its
//               lowest and highest y, in its own units; its index k in `profiles`)
//   kPolyhedron x0 y0 z0 x1 y1 z1 k          (its box; its index k in `surfaces`)
//
// Extrusions and revolutions evaluate their 2D profile, compiled (core/geometry/program.h) and
// kept in `profiles`; the view points at one 2D view per profile. A polyhedron's triangles, in
// their hierarchy (triangle_surface3.h), are kept in `surfaces` the same way.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/geometry/program.h"
#include "core/geometry3d/triangle_surface3.h"

namespace meshd {

constexpr int kMaxProgram3Stack = 40;

enum class Op3 : uint32_t {
  kSphere,
  kCuboid,
  kCylinder,
  kFrustum,
  kTorus,
  kHalfSpace,
  kExtrusion,
  kRevolution,
  kPolyhedron,
  kMin,
  kMax,
  kNegate,
};

struct Instruction3 {
  Op3 op;
  uint32_t operand;   // primitives: offset into params; 0 for operations
  int32_t primitive;  // index into Program3::primitives; -1 for operations
};

// What the host needs to know about each primitive beyond its distance.
struct PrimitiveInfo3 {
  std::string name;  // boundary group name ("<kind><index>" when the request gave none)
  std::string path;  // request field path of the primitive's node, for errors
};

// Trivially copyable view of a program, passed by value to device code.
struct Program3View {
  const Instruction3* code;
  uint32_t size;
  const double* params;
  const ProgramView* profiles;           // one per 2D profile
  const TriangleSurface3View* surfaces;  // one per polyhedron
};

struct Program3 {
  std::vector<Instruction3> code;
  std::vector<double> params;
  std::vector<PrimitiveInfo3> primitives;
  std::string root_path;  // the tree's root, for errors about the whole domain
  // The 2D profiles and their views, shared so that a copy of the program keeps valid views.
  std::vector<std::shared_ptr<const Program>> profiles;
  std::shared_ptr<std::vector<ProgramView>> profile_views =
      std::make_shared<std::vector<ProgramView>>();
  // The polyhedra's surfaces and their views, shared likewise.
  std::vector<std::shared_ptr<const TriangleSurface3>> surfaces;
  std::shared_ptr<std::vector<TriangleSurface3View>> surface_views =
      std::make_shared<std::vector<TriangleSurface3View>>();

  Program3View view() const {
    return {code.data(), static_cast<uint32_t>(code.size()), params.data(), profile_views->data(),
            surface_views->data()};
  }
};

}  // namespace meshd
