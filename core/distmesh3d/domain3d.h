// What the 3D DistMesh loop needs to know of a domain: its signed distance, the size field, a
// box around it, the nodes it must keep fixed and the boundary groups.
//
// Plain callables, so that the loop (distmesh3d.h) does not care where they come from: the
// compiled 3D geometry (core/geometry3d/) or a test's own function.
#pragma once

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "core/common/vec3.h"

namespace meshd {

struct Program3;
struct CompiledSizeField3;

struct Domain3 {
  // Signed distance, negative inside, in the request's length unit: exact near the boundary
  // (GeometryDomain3's exact band), beyond it perhaps only a bound with the right sign.
  std::function<double(Vec3)> distance;
  // Relative desired edge length h(p) > 0 (DistMesh's fh); empty for a uniform field.
  std::function<double(Vec3)> size;
  // Contains the whole domain.
  Box3 bounds;
  // Nodes that never move (sharp corners and samples along sharp edges), #F by 3.
  std::vector<Vec3> fixed;
  // The boundary group of a point on the boundary, an index into `boundary_names`; empty: one
  // group named "boundary".
  std::function<int(Vec3)> boundary_group;
  std::vector<std::string> boundary_names;

  // The compiled forms of `distance` and `size`, for an engine that evaluates them itself (the
  // GPU's): distance = eval_sdf3(program, p, nullptr, exact_band), size = eval_size3(size_field)
  // where `size` is set. Null for a test's own callables, which only the CPU engine runs.
  const Program3* program = nullptr;
  double exact_band = INFINITY;
  const CompiledSizeField3* size_field = nullptr;
};

}  // namespace meshd
