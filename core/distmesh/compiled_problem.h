// A Problem compiled for the engines: flat programs for the distance and the size field, the
// box for the initial points, and every fixed node (given ones and detected corners).
#pragma once

#include <cstdint>
#include <vector>

#include "core/distmesh/problem.h"
#include "core/geometry/program.h"
#include "core/geometry/size_program.h"

namespace meshd {

struct CompiledProblem {
  Program geometry;
  SizeProgram size;
  Box bbox;
  double h0 = 0.0;
  std::vector<Vec2> fixed_points;  // #F by 2, no duplicates; they become nodes 0..F-1
  Params params;
  uint64_t seed = 0;
};

// Compiles `problem`. Throws Error(kInvalidArgument) naming the field when the geometry is
// unbounded without a bbox, the bbox or domain is empty, or a fixed point lies outside.
CompiledProblem compile_problem(const Problem& problem);

// The corners of `geometry`'s final boundary (|d| tiny there): polygon and rectangle vertices
// where the outline turns by kMinCrossingDegrees or more, and the crossings of two primitives'
// boundaries (boundary_crossings.h).
// Throws Error(kInvalidArgument) on field "geometry" past kMaxCrossingCorners crossings.
std::vector<Vec2> boundary_corners(const Program& geometry, const Box& bbox);
constexpr size_t kMaxCrossingCorners = 20000;

}  // namespace meshd
