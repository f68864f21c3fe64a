// Positions along a Hilbert curve over a bounding box (spatial_order.h), shared by the host's
// renumbering and the GPU engine's, so that both give the same order.
#pragma once

#include <cstdint>

#include "core/common/hd.h"
#include "core/common/vec2.h"

namespace meshd {

constexpr int kHilbertBits = 16;  // a 65,536 x 65,536 grid: far finer than any node spacing
constexpr uint32_t kHilbertCells = 1u << kHilbertBits;

// Distance of cell (x, y) along the Hilbert curve of order kHilbertBits (the classic rotate
// and flip per level, from the coarsest quadrant down).
MESHD_HD inline uint32_t hilbert_index(uint32_t x, uint32_t y) {
  uint32_t d = 0;
  for (uint32_t s = 1u << (kHilbertBits - 1); s > 0; s >>= 1) {
    const uint32_t rx = (x & s) ? 1 : 0;
    const uint32_t ry = (y & s) ? 1 : 0;
    d += s * s * ((3 * rx) ^ ry);
    if (ry == 0) {    // rotate the quadrant so that the curve's pieces join up
      if (rx == 1) {  // flipping every bit flips the lower ones, which the next levels read
        x = kHilbertCells - 1 - x;
        y = kHilbertCells - 1 - y;
      }
      const uint32_t swap = x;
      x = y;
      y = swap;
    }
  }
  return d;
}

// The curve's grid over a bounding box [lo, hi]: one scale for both axes keeps its cells square.
struct HilbertFrame {
  Vec2 lo;
  double scale;

  MESHD_HD static HilbertFrame over(Vec2 lo, Vec2 hi) {
    const double extent = hi.x - lo.x > hi.y - lo.y ? hi.x - lo.x : hi.y - lo.y;
    return {lo, extent > 0.0 ? (kHilbertCells - 1) / extent : 0.0};
  }
  MESHD_HD uint32_t cell(double v, double origin) const {
    const double c = (v - origin) * scale;
    return static_cast<uint32_t>(c < 0.0 ? 0.0
                                         : (c > kHilbertCells - 1.0 ? kHilbertCells - 1.0 : c));
  }
  MESHD_HD uint32_t key(Vec2 p) const { return hilbert_index(cell(p.x, lo.x), cell(p.y, lo.y)); }
};

}  // namespace meshd
