#include "core/distmesh/node_estimate.h"

#include <algorithm>
#include <cmath>
#include <sstream>

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
  if (!(w > 0 && hgt > 0 && std::isfinite(w) && std::isfinite(hgt))) {
    std::ostringstream box;
    box << "[" << c.bbox.min.x << ", " << c.bbox.max.x << "] x [" << c.bbox.min.y << ", "
        << c.bbox.max.y << "]";
    throw_invalid("geometry", "the domain's box (clipped to bbox when one is given) is " +
                                  box.str() + "; its width and height must be finite and > 0");
  }
  const double cost = static_cast<double>(c.geometry.params.size() + c.size.shapes.params.size());
  const double samples = std::clamp(kWorkBudget / std::max(cost, 1.0), 64.0 * 64.0, kMaxSamples);
  // sqrt(w) sqrt(h) rather than sqrt(w h), which overflows for boxes near the double range; each
  // side between 1 and `samples` cells, so that a box far longer than wide (a 2.8e14 x 2
  // rectangle gave 4.7e9 columns) stays within the budget and the counts within int.
  const double cell = std::sqrt(w) * std::sqrt(hgt) / std::sqrt(samples);
  const int nx = static_cast<int>(std::clamp(std::ceil(w / cell), 1.0, samples));
  const int ny = static_cast<int>(std::clamp(std::ceil(hgt / cell), 1.0, samples));
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
