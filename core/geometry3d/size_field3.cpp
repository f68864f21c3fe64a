#include "core/geometry3d/size_field3.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "core/geometry3d/compile3d.h"
#include "core/geometry3d/sdf3_eval.cuh"

namespace meshd {

SizeRange size_range3(const SizeField3& field) {
  if (field.terms.empty()) return {1.0, 1.0};
  SizeRange out{INFINITY, INFINITY};
  for (const SizeTerm3& term : field.terms) {
    const SizeRange r =
        std::holds_alternative<UniformSize>(term)
            ? SizeRange{std::get<UniformSize>(term).value, std::get<UniformSize>(term).value}
            : SizeRange{std::get<DistanceSize3>(term).h_min, std::get<DistanceSize3>(term).h_max};
    out = {std::min(out.low, r.low), std::min(out.high, r.high)};
  }
  return out;
}

namespace {

// One distance term, its program kept alive by the callable's shared state.
struct CompiledDistanceSize3 {
  Program3 program;
  double h_min, slope, h_max;
};

}  // namespace

std::function<double(Vec3)> compile_size_field3(const SizeField3& field) {
  if (field.terms.empty()) return {};
  double uniform = INFINITY;
  auto terms = std::make_shared<std::vector<CompiledDistanceSize3>>();
  for (const SizeTerm3& term : field.terms) {
    if (const auto* u = std::get_if<UniformSize>(&term)) {
      uniform = std::min(uniform, u->value);
      continue;
    }
    const auto& d = std::get<DistanceSize3>(term);
    terms->push_back({compile_geometry3(d.shape), d.h_min, d.slope, d.h_max});
  }
  return [terms, uniform](Vec3 p) {
    double h = uniform;
    for (const CompiledDistanceSize3& t : *terms) {
      const double d = std::abs(eval_sdf3(t.program.view(), p));
      h = std::min(h, std::min(t.h_max, t.h_min + t.slope * d));
    }
    return h;
  };
}

}  // namespace meshd
