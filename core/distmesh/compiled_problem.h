// A Problem compiled for the engines: flat programs for the distance and the size field, the
// box for the initial points, and every fixed node (given ones and detected corners).
#pragma once

#include <cstdint>
#include <vector>

#include "core/distmesh/problem.h"
#include "core/geometry/program.h"
#include "core/geometry/size_program.h"

namespace meshd {

class ThreadPool;

struct CompiledProblem {
  Program geometry;
  double lipschitz = 1.0;  // of the geometry's distance (lipschitz.h)
  SizeProgram size;
  Box bbox;
  double h0 = 0.0;
  std::vector<Vec2> fixed_points;  // #F by 2, no duplicates; they become nodes 0..F-1
  Params params;
  uint64_t seed = 0;
  // The integral of 1 / h^2 over the domain (node_estimate.h) once a survey has taken it, 0
  // before: it holds for any h0, so that the multilevel levels and the service's worker count
  // nodes without sampling the domain again (a 60-vertex airfoil's survey is 14 ms).
  double inverse_size_integral = 0.0;
};

// Compiles `problem`; feature-size terms and a gradation are sampled as sampled_size_field's.
// With auto_corners, the boundary's corners join the fixed points, thinned where they crowd
// (corner_clusters.h).
// Throws Error(kInvalidArgument) naming the field when the geometry is unbounded without a bbox,
// the bbox or domain is empty, or a fixed point lies outside.
CompiledProblem compile_problem(const Problem& problem);

// `problem.size` with what needs the domain sampled on grids over the domain's box, at half the
// finest edge: each feature-size term becomes its grid (feature_size.h); then a gradation
// limits the growth of the edge length h0 * h to `gradation` per length unit (gradation.h),
// the whole field becoming one grid term. The result has no gradation and no feature-size term;
// a field that has neither comes back as it is. The field compile_problem meshes with; the
// service applies it once, when it converts a request. Throws as compile_problem does for an
// empty or unbounded domain. The gradation's samples run over `pool`'s threads when one is given.
SizeFieldSpec sampled_size_field(const Problem& problem, ThreadPool* pool = nullptr);

// The corners of `geometry`'s final boundary (|d| tiny there): polygon and rectangle vertices
// where the outline turns by kMinCrossingDegrees or more, and the crossings of two primitives'
// boundaries (boundary_crossings.h). turns: null, or filled with each corner's turn (radians in
// [0, pi], |pi - the angle between the outline's two sides there) where a polygon's or a
// rectangle's outline gives it, NaN at crossings.
// Throws Error(kInvalidArgument) on field "geometry" past kMaxCrossingCorners crossings.
std::vector<Vec2> boundary_corners(const Program& geometry, const Box& bbox,
                                   std::vector<double>* turns = nullptr);
constexpr size_t kMaxCrossingCorners = 20000;

}  // namespace meshd
