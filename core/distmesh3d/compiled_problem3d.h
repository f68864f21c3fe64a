// A Problem3 compiled once for its job: the geometry's program, the size field scaled to the
// loop's h0, and the distance band the loop needs exact (the twin of compiled_problem.h). The
// service compiles a request when it converts it, checks its node count on this, and hands the
// same compilation to the worker: a polyhedron's surface is built and checked for crossings once.
#pragma once

#include <memory>

#include "core/distmesh3d/params3d.h"
#include "core/distmesh3d/problem3d.h"
#include "core/geometry3d/program3d.h"
#include "core/geometry3d/size_field3.h"

namespace meshd {

struct CompiledProblem3 {
  std::shared_ptr<const Program3> geometry;
  // Every value divided by the field's smallest bound (range.low), so that h >= 1.
  std::shared_ptr<const CompiledSizeField3> size;
  bool uniform = true;        // the field has no terms (h = 1)
  SizeRange range{1.0, 1.0};  // the request's field's bounds (size_range3)
  double request_h0 = 0.0;    // the request's h0: the edge where h is at its smallest bound
  double h0 = 0.0;            // request_h0 * range.low: the loop's finest edge
  // The distance is exact within this of the boundary (kExactDistanceEdges of the largest
  // edges), and at least this beyond it.
  double exact_band = 0.0;
  bool auto_features = true;
  Params3 params;
};

// Compiles `problem`. Throws Error(kInvalidArgument) naming the field of a bad shape (the
// geometry's or a size term's), as compile_geometry3 does.
CompiledProblem3 compile_problem3(const Problem3& problem);

}  // namespace meshd
