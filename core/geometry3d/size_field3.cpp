#include "core/geometry3d/size_field3.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "core/geometry3d/compile3d.h"

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

std::shared_ptr<const CompiledSizeField3> compile_size_field3(const SizeField3& field,
                                                              double divisor) {
  auto out = std::make_shared<CompiledSizeField3>();
  out->divisor = divisor;
  for (const SizeTerm3& term : field.terms) {
    if (const auto* u = std::get_if<UniformSize>(&term)) {
      out->uniform = std::min(out->uniform, u->value);
      continue;
    }
    const auto& d = std::get<DistanceSize3>(term);
    out->terms.push_back({compile_geometry3(d.shape), d.h_min, d.slope, d.h_max});
  }
  for (const auto& t : out->terms)
    out->views.push_back({t.program.view(), t.h_min, t.slope, t.h_max});
  return out;
}

std::function<double(Vec3)> size_callable3(std::shared_ptr<const CompiledSizeField3> field,
                                           bool uniform) {
  if (uniform) return {};
  return [field = std::move(field)](Vec3 p) { return eval_size3(field->view(), p); };
}

std::function<double(Vec3)> compile_size_field3(const SizeField3& field) {
  return size_callable3(compile_size_field3(field, 1.0), field.terms.empty());
}

}  // namespace meshd
