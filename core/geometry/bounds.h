// The bounding box of a compiled geometry, derived from the tree: a union covers its operands'
// boxes, an intersection their overlap, a difference its base (a negated operand is unbounded).
#pragma once

#include "core/common/vec2.h"
#include "core/geometry/program.h"

namespace meshd {

// Box of program instructions [begin, end). Infinite coordinates mean unbounded in that
// direction; min > max means empty.
Box program_bounds(const Program& program, uint32_t begin, uint32_t end);
inline Box program_bounds(const Program& program) {
  return program_bounds(program, 0, static_cast<uint32_t>(program.code.size()));
}

// A box B of instructions [begin, end) such that their value at any p outside B is at least
// the distance from p to B: what lets an indexed union skip an operand (sdf_eval.cuh). Unlike
// program_bounds, an intersection or a difference takes one operand's box (the smallest), not
// the overlap: max(a, b) >= a, but a point near two long crossing boxes can lie much farther
// from their overlap than from either.
Box distance_bound_box(const Program& program, uint32_t begin, uint32_t end);

inline bool is_bounded(const Box& b) {
  return std::isfinite(b.min.x) && std::isfinite(b.min.y) && std::isfinite(b.max.x) &&
         std::isfinite(b.max.y);
}
inline bool is_empty(const Box& b) { return b.min.x > b.max.x || b.min.y > b.max.y; }

}  // namespace meshd
