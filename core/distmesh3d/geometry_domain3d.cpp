#include "core/distmesh3d/geometry_domain3d.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "core/geometry3d/bounds3.h"
#include "core/geometry3d/compile3d.h"
#include "core/geometry3d/crease_features3.h"
#include "core/geometry3d/sdf3_eval.cuh"
#include "core/geometry3d/sharp_features3.h"

namespace meshd {

GeometryDomain3::GeometryDomain3(std::shared_ptr<const Program3> program, double h0,
                                 std::function<double(Vec3)> size, bool sharp_features,
                                 double exact_band)
    : program_(std::move(program)) {
  // Primitives that share a name share a boundary group, in the order of first appearance.
  for (const PrimitiveInfo3& info : program_->primitives) {
    auto& names = domain_.boundary_names;
    const auto it = std::find(names.begin(), names.end(), info.name);
    group_of_primitive_.push_back(static_cast<int>(it - names.begin()));
    if (it == names.end()) names.push_back(info.name);
  }
  const Program3View view = program_->view();
  domain_.distance = [view, exact_band](Vec3 p) { return eval_sdf3(view, p, nullptr, exact_band); };
  domain_.program = program_.get();
  domain_.exact_band = exact_band;
  domain_.size = std::move(size);
  domain_.boundary_group = [this, view](Vec3 p) {
    int owner = 0;
    eval_sdf3(view, p, &owner);
    return owner >= 0 ? group_of_primitive_[owner] : 0;
  };
  domain_.bounds = domain_bounds3(*program_);
  if (!sharp_features) return;

  // Sharp edges sampled at the finest size along them: a spacing that varied along an edge
  // would need the sampling to follow the field (left for later); a uniform field needs none.
  double spacing = h0;
  if (domain_.size) {
    double h_min = INFINITY;
    for (const Vec3& p : sharp_features3(*program_, h0)) h_min = std::min(h_min, domain_.size(p));
    if (std::isfinite(h_min)) spacing = h0 * h_min;
  }
  domain_.fixed = sharp_features3(*program_, spacing);
  const std::vector<Vec3> creases =
      crease_features3(*program_, domain_.bounds, spacing, domain_.fixed);
  domain_.fixed.insert(domain_.fixed.end(), creases.begin(), creases.end());
}

GeometryDomain3::GeometryDomain3(const Shape3& shape, double h0, std::function<double(Vec3)> size,
                                 bool sharp_features, double exact_band)
    : GeometryDomain3(std::make_shared<const Program3>(compile_geometry3(shape)), h0,
                      std::move(size), sharp_features, exact_band) {}

GeometryDomain3::GeometryDomain3(std::shared_ptr<const Program3> program, double h0,
                                 std::shared_ptr<const CompiledSizeField3> size_field, bool uniform,
                                 bool sharp_features, double exact_band)
    : GeometryDomain3(std::move(program), h0, size_callable3(size_field, uniform), sharp_features,
                      exact_band) {
  size_field_ = std::move(size_field);
  if (!uniform) domain_.size_field = size_field_.get();
}

}  // namespace meshd
