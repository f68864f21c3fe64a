// Compiles the 3D geometry tree to a flat program (program3d.h).
#pragma once

#include "core/geometry3d/program3d.h"
#include "core/geometry3d/shape3d.h"

namespace meshd {

// The postfix program of `root`, transforms folded into the primitives. Unnamed primitives get
// "<kind><index>" names (sphere1, cuboid2, half_space1, ...). Throws Error(kInvalidArgument)
// naming the field and its allowed range for a bad parameter: the field is the node's path, its
// kind and the parameter ("<path>.sphere.radius", "<path>.transform.axis"); a CSG with no
// operand names "<path>.union.shapes" (or intersection, difference); a tree that needs more than
// kMaxProgram3Stack values to evaluate names the node's path.
Program3 compile_geometry3(const Shape3& root);

}  // namespace meshd
