// Validity checks for a polygon given as a vertex list, before it becomes a Polygon primitive.
//
// A polygon is simple when its boundary never meets itself except where neighbouring edges share
// their vertex. Edge i joins vertex i to vertex i+1 (mod #V); every message uses that numbering.
#pragma once

#include <string>
#include <vector>

#include "core/common/vec2.h"

namespace meshd {

// Throws Error(kInvalidArgument, path + ".vertices", ...) unless `vertices` is a simple polygon:
// at least 3 finite vertices, no two equal (the first is not repeated at the end), not all on
// one line, no edge turning back along its neighbour, no two non-neighbouring edges crossing or
// touching. The message says what is wrong and where ("edges 2 and 5 cross near (0.4, 0.1)").
// Either orientation is fine. Exact predicates; O(#V log #V) by a Shamos-Hoey sweep.
//
//   vertices  #V by 2, in length units
//   path      request field path of the polygon message, e.g. "geometry.polygon"
void check_simple_polygon(const std::vector<Vec2>& vertices, const std::string& path);

}  // namespace meshd
