// The 3D geometry as a tree, in plain C++: what a request describes after conversion.
//
// Distances are signed, negative inside. Operations follow the usual CSG algebra on signed
// distance functions: union = min, intersection = max, difference a \ b = max(a, -b). Transforms
// are similarities (rotation, uniform scale, translation), so the compiler folds them into the
// primitives and every primitive distance stays exact.
//
// Each node keeps `path`, the request field it came from (the node itself, such as
// "geometry.union.shapes[2]"). The compiler names a bad parameter by that path, the node's kind
// and the field: "geometry.union.shapes[2].sphere.radius".
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <variant>
#include <vector>

#include "core/common/vec3.h"
#include "core/geometry/shape.h"  // CsgOp, shared with 2D

namespace meshd {

struct Sphere {
  Vec3 center;
  double radius = 0.0;  // > 0
};

// Axis-aligned before any enclosing transform.
struct Cuboid {
  Vec3 min;
  Vec3 max;  // max > min in every coordinate
};

// A finite cylinder with flat caps; its axis runs along +z from the centre of its base before
// any enclosing transform.
struct Cylinder {
  Vec3 base_center;
  double radius = 0.0;  // > 0
  double height = 0.0;  // > 0
};

// A truncated cone along +z from the centre of its base before any enclosing transform: a cone
// when one radius is 0 (its apex at that end), a cylinder when both are equal.
struct Frustum {
  Vec3 base_center;
  double bottom_radius = 0.0;  // >= 0, at base_center
  double top_radius = 0.0;     // >= 0, at base_center + height z; not both 0
  double height = 0.0;         // > 0
};

// A ring torus about the z axis through `center` before any enclosing transform.
struct Torus {
  Vec3 center;
  double major_radius = 0.0;  // > minor_radius: from the centre to the tube's centre line
  double minor_radius = 0.0;  // > 0: the tube's radius
};

// The closed half-space dot(normal, p) <= offset. normal need not be unit length.
struct HalfSpace {
  Vec3 normal;  // non-zero
  double offset = 0.0;
};

// A 2D shape (core/geometry/shape.h) in the xy plane, extruded along +z from z = 0 to `height`
// before any enclosing transform. Its distance is exact where the profile's is: the profile's
// and the slab's combined as a box's faces are.
struct Extrusion {
  Shape profile;        // bounded
  double height = 0.0;  // > 0
};

// A 2D shape revolved about the z axis before any enclosing transform: the profile's (x, y) are
// the solid's (distance from the axis, z), so only its part with x >= 0 counts. Exact where the
// profile's distance is and the profile either stays off the axis or is symmetric about it
// (where it crosses the axis asymmetrically, a bound near the axis).
struct Revolution {
  Shape profile;  // bounded, reaching x > 0, not touching x = 0 from one side only
};

// A closed triangle surface (triangle_surface3.h states what it must be): vertices before any
// enclosing transform and triangles of indices into them, turned either way.
struct Polyhedron {
  std::vector<Vec3> vertices;
  std::vector<std::array<int32_t, 3>> triangles;
};

struct Shape3;

// Union and intersection take one or more operands; difference is operands[0] minus the rest.
struct Csg3 {
  CsgOp op = CsgOp::kUnion;
  std::vector<Shape3> operands;  // at least one
};

// p -> scale * R(axis, angle) p + offset: rotate about the origin by `angle` radians
// (right-handed about `axis`), then scale, then translate.
struct Similarity3 {
  double scale = 1.0;        // > 0
  Vec3 axis{0.0, 0.0, 1.0};  // non-zero where angle != 0; need not be unit length
  double angle = 0.0;        // radians
  Vec3 offset;
};

// outer(inner(p)) as one similarity.
Similarity3 compose(const Similarity3& outer, const Similarity3& inner);
// scale * R p + offset.
Vec3 apply(const Similarity3& t, Vec3 p);
// R v alone: a direction, neither scaled nor moved.
Vec3 rotate(const Similarity3& t, Vec3 v);

// The operand is stored in a one-element vector so that Shape3 can stay a value type.
struct Transformed3 {
  Similarity3 transform;
  std::vector<Shape3> operand;  // exactly one
};

struct Shape3 {
  std::variant<Sphere, Cuboid, Cylinder, Frustum, Torus, HalfSpace, Extrusion, Revolution,
               Polyhedron, Csg3, Transformed3>
      node;
  std::string name;  // boundary group name for the primitives below; may be empty
  std::string path;  // request field path of this node, for errors
};

}  // namespace meshd
