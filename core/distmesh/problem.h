// Everything one mesh job needs, validated: the request after the service's conversion layer.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "core/common/vec2.h"
#include "core/distmesh/params.h"
#include "core/geometry/shape.h"
#include "core/geometry/size_field.h"

namespace meshd {

struct Problem {
  Shape geometry;
  SizeFieldSpec size;
  double h0 = 0.0;                 // absolute edge length where h(p) = 1; > 0
  std::optional<Box> bbox;         // derived from the geometry when absent
  std::vector<Vec2> fixed_points;  // kept as nodes, exactly
  bool auto_corners = true;        // boundary corners become fixed (corner_clusters.h)
  Params params;
  uint64_t seed = 0;  // for the size-based rejection of initial points
};

}  // namespace meshd
