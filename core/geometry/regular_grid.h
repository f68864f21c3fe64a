// Values sampled on a regular grid and read back by bilinear interpolation: the one grid that
// gridded size fields and signed-distance grids share, on the host and on the device.
//
// Layout: a grid's samples live in Program::samples (single precision, row by row: sample (i, j)
// at origin + (i * spacing.x, j * spacing.y) is samples[first + j * nx + i]); its header is
// kGridParams doubles in Program::params: ox oy dx dy nx ny first. nx, ny >= 2, dx, dy > 0.
#pragma once

#include <cstdint>

#include "core/common/hd.h"
#include "core/common/vec2.h"

namespace meshd {

struct Program;

constexpr uint32_t kGridParams = 7;

struct RegularGrid {
  Vec2 origin;
  Vec2 spacing;
  uint32_t nx = 0;
  uint32_t ny = 0;
  const float* values = nullptr;  // nx * ny, row by row

  MESHD_HD double at(uint32_t i, uint32_t j) const { return values[size_t(j) * nx + i]; }
  MESHD_HD Box box() const {
    return {origin, {origin.x + (nx - 1) * spacing.x, origin.y + (ny - 1) * spacing.y}};
  }
};

// The grid whose header starts at params[offset], over `samples`.
MESHD_HD inline RegularGrid grid_at(const double* params, const float* samples, uint32_t offset) {
  const double* h = params + offset;
  return {{h[0], h[1]},
          {h[2], h[3]},
          static_cast<uint32_t>(h[4]),
          static_cast<uint32_t>(h[5]),
          samples + static_cast<size_t>(h[6])};
}

// Bilinear interpolation at p; outside the grid's box, the value at the nearest point of the box
// (the border samples extend outwards).
MESHD_HD inline double bilinear(const RegularGrid& g, Vec2 p) {
  const double u = (p.x - g.origin.x) / g.spacing.x, v = (p.y - g.origin.y) / g.spacing.y;
  const double uc = fmin(fmax(u, 0.0), double(g.nx - 1)), vc = fmin(fmax(v, 0.0), double(g.ny - 1));
  const uint32_t i = static_cast<uint32_t>(fmin(floor(uc), double(g.nx - 2)));
  const uint32_t j = static_cast<uint32_t>(fmin(floor(vc), double(g.ny - 2)));
  const double s = uc - i, t = vc - j;
  const double bottom = (1.0 - s) * g.at(i, j) + s * g.at(i + 1, j);
  const double top = (1.0 - s) * g.at(i, j + 1) + s * g.at(i + 1, j + 1);
  return (1.0 - t) * bottom + t * top;
}

// Appends a grid to `program` (its header to params, its values to samples) and returns the
// header's offset in params, for an instruction's operand or a size term. `values` holds nx * ny
// samples row by row; the caller has validated the sizes and the spacing.
uint32_t append_grid(Program& program, Vec2 origin, Vec2 spacing, uint32_t nx, uint32_t ny,
                     const float* values);

}  // namespace meshd
