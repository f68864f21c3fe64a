#include "core/geometry/boundary_samples.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "core/geometry/sdf_eval.cuh"

namespace meshd {
namespace {

// Two Newton steps onto the zero level of the distance, with a central-difference gradient.
Vec2 project(ProgramView view, Vec2 p, double step) {
  for (int i = 0; i < 2; ++i) {
    const double d = eval_sdf(view, p);
    const Vec2 g{
        (eval_sdf(view, {p.x + step, p.y}) - eval_sdf(view, {p.x - step, p.y})) / (2 * step),
        (eval_sdf(view, {p.x, p.y + step}) - eval_sdf(view, {p.x, p.y - step})) / (2 * step)};
    const double g2 = g.x * g.x + g.y * g.y;
    if (!(g2 > 0.0)) break;
    p = {p.x - d * g.x / g2, p.y - d * g.y / g2};
  }
  return p;
}

// Keeps a point unless one kept lies within `radius`, in a hash grid of cells `radius` wide.
class Thinned {
 public:
  Thinned(std::vector<Vec2>& out, double radius) : out_(out), radius_(radius) {}
  void add(Vec2 p) {
    const double cx = std::floor(p.x / radius_), cy = std::floor(p.y / radius_);
    for (double dx = -1; dx <= 1; ++dx)
      for (double dy = -1; dy <= 1; ++dy) {
        const auto it = cells_.find(key(cx + dx, cy + dy));
        if (it == cells_.end()) continue;
        for (size_t i : it->second) {
          const double ex = out_[i].x - p.x, ey = out_[i].y - p.y;
          if (ex * ex + ey * ey < radius_ * radius_) return;
        }
      }
    cells_[key(cx, cy)].push_back(out_.size());
    out_.push_back(p);
  }

 private:
  static std::pair<double, double> key(double x, double y) { return {x, y}; }
  struct Hash {
    size_t operator()(const std::pair<double, double>& k) const {
      return std::hash<double>()(k.first) ^ (std::hash<double>()(k.second) * 0x9e3779b97f4a7c15ull);
    }
  };
  std::vector<Vec2>& out_;
  double radius_;
  std::unordered_map<std::pair<double, double>, std::vector<size_t>, Hash> cells_;
};

}  // namespace

std::vector<Vec2> boundary_samples(const Program& program, const Box& box, double spacing,
                                   const std::vector<Vec2>& corners) {
  const ProgramView view = program.view();
  const double width = box.max.x - box.min.x, height = box.max.y - box.min.y;
  double cell = 0.25 * spacing;
  const auto vertices = [&](double c) { return (width / c + 3) * (height / c + 3); };
  while (vertices(cell) > kMaxBoundaryGridPoints) cell *= 1.5;
  const int nx = static_cast<int>(std::ceil(width / cell)) + 3;
  const int ny = static_cast<int>(std::ceil(height / cell)) + 3;
  const Vec2 origin{box.min.x - cell, box.min.y - cell};
  std::vector<double> d(static_cast<size_t>(nx) * ny);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
      d[static_cast<size_t>(j) * nx + i] =
          eval_sdf(view, {origin.x + i * cell, origin.y + j * cell});

  std::vector<Vec2> out;
  Thinned kept(out, 0.75 * spacing);
  for (Vec2 c : corners) kept.add(c);
  const double step = 1e-3 * cell;
  const auto crossing = [&](int i0, int j0, int i1, int j1) {
    const double a = d[static_cast<size_t>(j0) * nx + i0], b = d[static_cast<size_t>(j1) * nx + i1];
    if ((a < 0.0) == (b < 0.0) || !std::isfinite(a) || !std::isfinite(b)) return;
    const double t = a / (a - b);
    const Vec2 p{origin.x + (i0 + t * (i1 - i0)) * cell, origin.y + (j0 + t * (j1 - j0)) * cell};
    kept.add(project(view, p, step));
  };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      if (i + 1 < nx) crossing(i, j, i + 1, j);
      if (j + 1 < ny) crossing(i, j, i, j + 1);
    }
  return out;
}

}  // namespace meshd
