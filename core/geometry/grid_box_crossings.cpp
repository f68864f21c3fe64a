#include "core/geometry/grid_box_crossings.h"

#include <cmath>

#include "core/geometry/boundary_crossings.h"
#include "core/geometry/regular_grid.h"

namespace meshd {

void grid_box_crossings(const Program& program, const Instruction& ins, std::vector<Vec2>& out) {
  const RegularGrid g = grid_at(program.params.data(), program.samples.data(), ins.operand);
  const double* t = program.params.data() + ins.operand + kGridParams;  // tx ty cos sin scale
  const double min_sin = std::sin(kMinCrossingDegrees * 3.14159265358979323846 / 180.0);
  auto to_world = [&](Vec2 l) {
    return Vec2{t[0] + t[4] * (t[2] * l.x - t[3] * l.y), t[1] + t[4] * (t[3] * l.x + t[2] * l.y)};
  };
  // One side: n samples from (i0, j0) in steps (di, dj); (ni, nj) steps inwards, to the next row
  // or column, which gives the derivative across the side.
  auto side = [&](uint32_t i0, uint32_t j0, int di, int dj, int ni, int nj, uint32_t n) {
    const double along = di != 0 ? g.spacing.x : g.spacing.y;
    const double across = ni != 0 ? g.spacing.x : g.spacing.y;
    for (uint32_t k = 0; k + 1 < n; ++k) {
      const uint32_t ia = i0 + di * k, ja = j0 + dj * k, ib = ia + di, jb = ja + dj;
      const double a = g.at(ia, ja), b = g.at(ib, jb);
      if ((a < 0.0) == (b < 0.0)) continue;
      const double s = a / (a - b);
      // The interpolant's gradient there, along the side and across it (into the box).
      const double g_along = (b - a) / along;
      const double g_across =
          ((1 - s) * (g.at(ia + ni, ja + nj) - a) + s * (g.at(ib + ni, jb + nj) - b)) / across;
      if (std::fabs(g_along) < min_sin * std::hypot(g_along, g_across)) continue;  // a tangent
      out.push_back(to_world(
          {g.origin.x + (ia + s * di) * g.spacing.x, g.origin.y + (ja + s * dj) * g.spacing.y}));
    }
  };
  const uint32_t last_i = g.nx - 1, last_j = g.ny - 1;
  side(0, 0, 1, 0, 0, 1, g.nx);        // bottom
  side(0, last_j, 1, 0, 0, -1, g.nx);  // top
  side(0, 0, 0, 1, 1, 0, g.ny);        // left
  side(last_i, 0, 0, 1, -1, 0, g.ny);  // right
}

}  // namespace meshd
