// Step 1-2 of DistMesh, per grid point, shared by the CPU and GPU engines so that both start
// from the same points: an equilateral grid over the box (rows about h0 * sqrt(3)/2 apart,
// every other row shifted by half a column), points with fd < geps kept, then each kept where
// (h_min / h(p))^2 exceeds its threshold, an ordered dither of (seed, grid column, row) that
// needs no shared random state and gives the same answer wherever it is evaluated.
#pragma once

#include <cstdint>

#include "core/common/hd.h"
#include "core/common/vec2.h"

namespace meshd {

struct InitialGrid {
  Vec2 origin;
  double h0;   // the h0 asked for
  double dx;   // column spacing: h0 stretched so that columns land on both sides of the box
  double dy;   // row spacing: h0 sqrt(3)/2 stretched so that rows land on its bottom and top
  int64_t nx;  // points per row
  int64_t ny;  // rows
};

// The grid spans the box exactly: with DistMesh's min-anchored grid the far sides of a box-shaped
// domain get no points, and the convex hull then joins the corners by one long edge whose sliver
// triangle passes the centroid test and inflates the L0 scale for every bar (G2 at 300k nodes
// started with bars of 500 h0). Stretching by less than half a spacing over the box costs
// nothing in quality.
MESHD_HD inline InitialGrid make_initial_grid(Box bbox, double h0) {
  const double w = bbox.max.x - bbox.min.x, h = bbox.max.y - bbox.min.y;
  const double row = h0 * 0.8660254037844386;  // sqrt(3)/2
  InitialGrid g;
  g.origin = bbox.min;
  g.h0 = h0;
  const int64_t cols = static_cast<int64_t>(w / h0 + 0.5),
                rows = static_cast<int64_t>(h / row + 0.5);
  g.dx = cols > 0 ? w / static_cast<double>(cols) : h0;
  g.dy = rows > 0 ? h / static_cast<double>(rows) : row;
  g.nx = cols + 1;
  g.ny = rows + 1;
  // A box 1.5 to 2.5 rows high: spanning it would put two of its three rows on the boundary,
  // where a domain that thin (an ellipse two edges across) keeps only the middle row, collinear
  // points that triangulate to nothing. Its rows keep their spacing and are centred instead.
  if (rows == 2) {
    const double intervals = floor(h / row);
    g.dy = row;
    g.ny = static_cast<int64_t>(intervals) + 1;
    g.origin.y = bbox.min.y + 0.5 * (h - intervals * row);
  }
  return g;
}

MESHD_HD inline Vec2 initial_grid_point(const InitialGrid& g, int64_t index) {
  const int64_t j = index / g.nx, i = index % g.nx;
  return {g.origin.x + g.dx * (static_cast<double>(i) + ((j & 1) ? 0.5 : 0.0)),
          g.origin.y + g.dy * static_cast<double>(j)};
}

// The seed's 64 bits well mixed: splitmix64's finaliser.
MESHD_HD inline uint64_t mix_seed(uint64_t seed) {
  uint64_t z = seed + 0x9E3779B97F4A7C15ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

// The threshold in [0, 1) of grid point `index` for the rejection test: Roberts' R2 sequence
// over the point's (column, row), shifted by the seed, in 64-bit fixed point so that every
// compiler and device computes the same bits. Neighbouring points get thresholds spread evenly
// over [0, 1), so that the kept points follow (h_min / h)^2 closely at every scale (an ordered
// dither). An independent draw per point (DistMesh's rand) left density noise at every
// wavelength, which the spring network's long modes took hundreds of iterations to even out:
// graded requests of 2,000 nodes ran 5-6x the iterations of uniform ones.
MESHD_HD inline double dither_threshold(uint64_t seed, const InitialGrid& g, int64_t index) {
  constexpr uint64_t kColumnStep = 0xC13FA9A902A6328Full;  // 2^64 / p, p the plastic number
  constexpr uint64_t kRowStep = 0x91E10DA5C79E7B1Cull;     // 2^64 / p^2
  const auto column = static_cast<uint64_t>(index % g.nx),
             row = static_cast<uint64_t>(index / g.nx);
  const uint64_t t = mix_seed(seed) + column * kColumnStep + row * kRowStep;  // modulo 2^64
  return static_cast<double>(t >> 11) * 0x1.0p-53;
}

// The rejection test of step 2: keep with probability r0 / max(r0), r0 = 1 / h^2.
MESHD_HD inline bool keep_by_size(uint64_t seed, const InitialGrid& g, int64_t index, double h,
                                  double h_min) {
  const double ratio = h_min / h;
  return dither_threshold(seed, g, index) < ratio * ratio;
}

}  // namespace meshd
