#include "core/geometry/size_field.h"

#include <algorithm>
#include <cmath>

namespace meshd {

SizeRange size_term_range(const SizeTerm& term) {
  if (const auto* u = std::get_if<UniformSize>(&term)) return {u->value, u->value};
  if (const auto* d = std::get_if<DistanceSize>(&term)) return {d->h_min, d->h_max};
  if (const auto* f = std::get_if<FeatureSize>(&term)) return {f->h_min, f->h_max};
  const auto& grid = std::get<GridSize>(term);
  if (grid.values.empty()) return {INFINITY, INFINITY};
  const auto [low, high] = std::minmax_element(grid.values.begin(), grid.values.end());
  return {grid.scale * *low, grid.scale * *high};
}

SizeRange size_field_range(const SizeFieldSpec& spec) {
  if (spec.terms.empty()) return {1.0, 1.0};
  SizeRange out{INFINITY, INFINITY};
  for (const auto& term : spec.terms) {
    const SizeRange r = size_term_range(term);
    out = {std::min(out.low, r.low), std::min(out.high, r.high)};
  }
  return out;
}

}  // namespace meshd
