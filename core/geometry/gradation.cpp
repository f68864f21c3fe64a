#include "core/geometry/gradation.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <queue>
#include <utility>
#include <vector>

#include "core/common/error.h"
#include "core/geometry/size_eval.cuh"

namespace meshd {
namespace {

struct Step {
  int di, dj;
};
constexpr Step kSteps[] = {{1, 0}, {-1, 0}, {0, 1},  {0, -1},  {1, 1}, {1, -1}, {-1, 1}, {-1, -1},
                           {1, 2}, {1, -2}, {-1, 2}, {-1, -2}, {2, 1}, {2, -1}, {-2, 1}, {-2, -1}};

}  // namespace

void limit_gradient(GridSize& grid, double g) {
  const int nx = static_cast<int>(grid.nx), ny = static_cast<int>(grid.ny);
  // The growth allowed along each step, in the grid's own units.
  double rise[std::size(kSteps)];
  for (size_t s = 0; s < std::size(kSteps); ++s)
    rise[s] = g * std::hypot(kSteps[s].di * grid.spacing.x, kSteps[s].dj * grid.spacing.y);

  // Double precision while settling, so that rounding cannot accumulate along long paths.
  std::vector<double> h(grid.values.begin(), grid.values.end());
  using Entry = std::pair<double, int64_t>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
  for (int64_t k = 0; k < static_cast<int64_t>(h.size()); ++k) queue.push({h[k], k});
  while (!queue.empty()) {
    const auto [value, k] = queue.top();
    queue.pop();
    if (value > h[k]) continue;  // lowered since it was queued: a newer entry settles it
    const int i = static_cast<int>(k % nx), j = static_cast<int>(k / nx);
    for (size_t s = 0; s < std::size(kSteps); ++s) {
      const int a = i + kSteps[s].di, b = j + kSteps[s].dj;
      if (a < 0 || b < 0 || a >= nx || b >= ny) continue;
      const int64_t n = static_cast<int64_t>(b) * nx + a;
      if (value + rise[s] < h[n]) {
        h[n] = value + rise[s];
        queue.push({h[n], n});
      }
    }
  }
  for (size_t k = 0; k < h.size(); ++k)
    grid.values[k] = std::min(grid.values[k], static_cast<float>(h[k]));
}

GridSize grid_over(const Box& box, double cell, const std::string& field) {
  const double w = box.max.x - box.min.x, hgt = box.max.y - box.min.y;
  if (!(w > 0 && hgt > 0 && std::isfinite(w) && std::isfinite(hgt) && cell > 0))
    throw_invalid(field, "needs a domain whose box has a finite width and height > 0");
  // Coarser than asked where the box holds too many cells: first to the budget's mean spacing,
  // then in small steps while the rounding up of a long side still exceeds it.
  cell = std::max(cell, std::sqrt(w * hgt / kMaxGradationSamples));
  double nx = 0, ny = 0;
  for (;; cell *= 1.05) {
    nx = std::ceil(w / cell) + 1, ny = std::ceil(hgt / cell) + 1;
    if (nx * ny <= kMaxGradationSamples) break;
  }
  GridSize grid;
  grid.origin = box.min;
  grid.nx = static_cast<uint32_t>(nx);
  grid.ny = static_cast<uint32_t>(ny);
  grid.spacing = {w / (nx - 1), hgt / (ny - 1)};
  grid.values.assign(static_cast<size_t>(grid.nx) * grid.ny, 0.0f);
  return grid;
}

GridSize limited_size_grid(const SizeProgram& size, const Box& box, double cell, double g) {
  GridSize grid = grid_over(box, cell, "size.gradation");
  grid.scale = size.terms.empty() ? 1.0 : INFINITY;
  for (const SizeTermCode& t : size.terms) grid.scale = std::min(grid.scale, t.h_min);
  const SizeView view = size.view();
  for (uint32_t j = 0; j < grid.ny; ++j)
    for (uint32_t i = 0; i < grid.nx; ++i) {
      const Vec2 p{grid.origin.x + i * grid.spacing.x, grid.origin.y + j * grid.spacing.y};
      grid.values[static_cast<size_t>(j) * grid.nx + i] =
          static_cast<float>(eval_size(view, p) / grid.scale);
    }
  limit_gradient(grid, g / grid.scale);
  return grid;
}

}  // namespace meshd
