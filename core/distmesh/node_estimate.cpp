#include "core/distmesh/node_estimate.h"

#include <algorithm>
#include <cmath>

#include "core/common/error.h"
#include "core/distmesh/compiled_problem.h"
#include "core/geometry/size_eval.cuh"

namespace meshd {
namespace {

// Up to 400 samples on the longer side of the box (a few percent on smooth domains), fewer when
// the distance is expensive (long polygons), so that the estimate stays under ~0.1 s.
constexpr double kMaxSamples = 400.0 * 400.0;
constexpr double kWorkBudget = 2e7;  // program parameters read, summed over samples

// integral over the domain of 1 / h(p)^2 dA, by the midpoint rule.
double inverse_size_integral(const CompiledProblem& c) {
  const double w = c.bbox.max.x - c.bbox.min.x, hgt = c.bbox.max.y - c.bbox.min.y;
  const double cost = static_cast<double>(c.geometry.params.size() + c.size.shapes.params.size());
  const double samples = std::clamp(kWorkBudget / std::max(cost, 1.0), 64.0 * 64.0, kMaxSamples);
  const double cell = std::sqrt(w * hgt / samples);
  const int nx = std::max(1, static_cast<int>(std::ceil(w / cell)));
  const int ny = std::max(1, static_cast<int>(std::ceil(hgt / cell)));
  const double dx = w / nx, dy = hgt / ny;
  double sum = 0.0;
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const Vec2 p{c.bbox.min.x + (i + 0.5) * dx, c.bbox.min.y + (j + 0.5) * dy};
      if (eval_sdf(c.geometry.view(), p) >= 0.0) continue;
      const double h = eval_size(c.size.view(), p);
      sum += 1.0 / (h * h);
    }
  }
  return sum * dx * dy;
}

}  // namespace

double estimate_node_count(const CompiledProblem& problem) {
  const double integral = inverse_size_integral(problem);
  if (integral <= 0.0)
    throw_invalid("geometry", "the domain is empty or thinner than its box / 400");
  return 2.0 / std::sqrt(3.0) * integral / (problem.h0 * problem.h0);
}

double estimate_node_count(const Problem& problem) {
  return estimate_node_count(compile_problem(problem));
}

double h0_for_node_count(const Problem& problem, double nodes) {
  return problem.h0 * std::sqrt(estimate_node_count(problem) / nodes);
}

}  // namespace meshd
