// Compiles the geometry tree and the size field to flat programs (program.h, size_program.h).
#pragma once

#include "core/geometry/program.h"
#include "core/geometry/shape.h"
#include "core/geometry/size_field.h"
#include "core/geometry/size_program.h"

namespace meshd {

// The postfix program of `root`, transforms folded into the primitives. Unnamed primitives get
// "<kind><index>" names (circle1, polygon2, ...). Throws Error(kInvalidArgument) naming the
// node's path when the tree needs more than kMaxProgramStack values to evaluate.
Program compile_geometry(const Shape& root);

// The size field's program; each distance term's shape becomes an instruction range, each grid
// term's samples a grid in the program (regular_grid.h). Feature-size terms and the gradation
// need the domain: sampled_size_field (compiled_problem.h) turns them into grids first; a
// feature-size term here is Error(kInternal).
SizeProgram compile_size_field(const SizeFieldSpec& spec);

// Whether an indexed union with a tree lies inside an operand of another (a coastline's land
// polygons, each with its lakes): an evaluator that follows one level of index, as the GPU's
// does by default (sdf_eval.cuh), folds the inner one in full at every point.
bool nests_indexed_unions(const Program& program);

}  // namespace meshd
