#include "core/geometry/feature_size.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/geometry/gradation.h"
#include "core/geometry/sdf_eval.cuh"

namespace meshd {

GridSize feature_size_grid(const Program& geometry, const FeatureSize& term, const Box& box,
                           double cell, double h0) {
  GridSize grid = grid_over(box, cell, "size.terms");
  const uint32_t nx = grid.nx, ny = grid.ny;
  auto at = [nx](uint32_t i, uint32_t j) { return static_cast<size_t>(j) * nx + i; };
  std::vector<double> d(grid.values.size());
  const ProgramView view = geometry.view();
  for (uint32_t j = 0; j < ny; ++j)
    for (uint32_t i = 0; i < nx; ++i)
      d[at(i, j)] =
          eval_sdf(view, {grid.origin.x + i * grid.spacing.x, grid.origin.y + j * grid.spacing.y});

  // The medial axis: inside samples (off the grid's border) whose gradient is short. Their
  // distance to the axis is 0, everyone else's starts unbounded and limit_gradient settles it.
  // A far distance stays within single precision: the box's diagonal bounds every real one.
  const double far = 2 * std::hypot((nx - 1) * grid.spacing.x, (ny - 1) * grid.spacing.y);
  GridSize axis = grid;
  std::fill(axis.values.begin(), axis.values.end(), static_cast<float>(far));
  for (uint32_t j = 1; j + 1 < ny; ++j)
    for (uint32_t i = 1; i + 1 < nx; ++i) {
      if (!(d[at(i, j)] < 0)) continue;
      const double gx = (d[at(i + 1, j)] - d[at(i - 1, j)]) / (2 * grid.spacing.x);
      const double gy = (d[at(i, j + 1)] - d[at(i, j - 1)]) / (2 * grid.spacing.y);
      if (std::hypot(gx, gy) < kRidgeGradient) axis.values[at(i, j)] = 0.0f;
    }
  limit_gradient(axis, 1.0);

  // Relative to h_min, so that single precision holds any magnitude (GridSize::scale).
  grid.scale = term.h_min;
  const double to_relative = 2.0 / (term.elements * h0);
  for (size_t k = 0; k < d.size(); ++k) {
    const double h =
        std::clamp((std::fabs(d[k]) + axis.values[k]) * to_relative, term.h_min, term.h_max);
    grid.values[k] = static_cast<float>(h / term.h_min);
  }
  return grid;
}

}  // namespace meshd
