#include "bench/cases3d.h"

#include <cmath>
#include <utility>

#include "core/common/error.h"

namespace meshd::bench {
namespace {

template <typename Node>
Shape3 shape(Node node, std::string name = "") {
  return Shape3{std::move(node), std::move(name), ""};
}

}  // namespace

Case3 case3d(const std::string& name) {
  if (name == "ball") return {shape(Sphere{{0, 0, 0}, 1.0}, "sphere"), 0.1, {}};
  if (name == "box_minus_sphere") {
    Csg3 difference{CsgOp::kDifference,
                    {shape(Cuboid{{-1, -1, -1}, {1, 1, 1}}, "box"),
                     shape(Sphere{{0, 0, 0}, 0.5}, "hole")}};
    return {shape(std::move(difference)), 0.1, {}};
  }
  if (name == "cylinder_graded") {
    // Three times finer on the axis than at the wall.
    return {shape(Cylinder{{0, 0, -1}, 1.0, 2.0}, "cylinder"), 0.05,
            [](Vec3 p) { return 1.0 + 2.0 * std::sqrt(p.x * p.x + p.y * p.y); }};
  }
  if (name == "torus") return {shape(Torus{{0, 0, 0}, 1.0, 0.4}, "torus"), 0.08, {}};
  throw Error(ErrorCode::kInvalidArgument, "domain", "must be one of " + case3d_names());
}

std::string case3d_names() { return "ball, box_minus_sphere, cylinder_graded, torus"; }

}  // namespace meshd::bench
