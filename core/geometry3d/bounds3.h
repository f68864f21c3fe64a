// The bounding box of a compiled 3D geometry, derived from the program: a union covers its
// operands' boxes, an intersection their overlap, a difference its base (a negated operand is
// unbounded). Exact for each primitive alone (the axis-aligned box of a rotated cuboid,
// cylinder, frustum or torus), conservative for CSG.
#pragma once

#include <cmath>

#include "core/common/vec3.h"
#include "core/geometry3d/program3d.h"

namespace meshd {

// Box holding every point where the program is <= 0. Infinite coordinates mean unbounded in
// that direction (a half-space is unbounded except along its normal where that is a coordinate
// axis); min > max in some coordinate means empty.
Box3 program_bounds3(const Program3& program);

// The same for a domain that must be meshed: throws Error(kInvalidArgument) when it is
// unbounded, naming the path of a half-space that nothing cuts off, or when the box is empty,
// naming the program's root path.
Box3 domain_bounds3(const Program3& program);

inline bool is_bounded(const Box3& b) {
  return std::isfinite(b.min.x) && std::isfinite(b.min.y) && std::isfinite(b.min.z) &&
         std::isfinite(b.max.x) && std::isfinite(b.max.y) && std::isfinite(b.max.z);
}
inline bool is_empty(const Box3& b) {
  return b.min.x > b.max.x || b.min.y > b.max.y || b.min.z > b.max.z;
}

}  // namespace meshd
