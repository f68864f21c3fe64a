#include "core/geometry/lipschitz.h"

#include <algorithm>
#include <cmath>

namespace meshd {

double bilinear_lipschitz(const RegularGrid& g) {
  // Within a cell the x slope is a convex combination of the x differences of its bottom and top
  // rows, and the y slope of its columns'; outside the box the clamp only flattens.
  double sx = 0.0, sy = 0.0;
  for (uint32_t j = 0; j < g.ny; ++j)
    for (uint32_t i = 0; i + 1 < g.nx; ++i)
      sx = std::max(sx, std::fabs(g.at(i + 1, j) - g.at(i, j)));
  for (uint32_t j = 0; j + 1 < g.ny; ++j)
    for (uint32_t i = 0; i < g.nx; ++i) sy = std::max(sy, std::fabs(g.at(i, j + 1) - g.at(i, j)));
  return std::hypot(sx / g.spacing.x, sy / g.spacing.y);
}

double distance_lipschitz(const Program& geometry) {
  double l = 1.0;
  for (const Instruction& ins : geometry.code) {
    if (ins.op != Op::kGrid) continue;
    // max(bilinear, box) in the grid's frame, mapped by a similarity: the slope carries over.
    const RegularGrid g = grid_at(geometry.params.data(), geometry.samples.data(), ins.operand);
    l = std::max(l, bilinear_lipschitz(g));
  }
  return l;
}

}  // namespace meshd
