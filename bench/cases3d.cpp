#include "bench/cases3d.h"

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
    Csg3 difference{
        CsgOp::kDifference,
        {shape(Cuboid{{-1, -1, -1}, {1, 1, 1}}, "box"), shape(Sphere{{0, 0, 0}, 0.5}, "hole")}};
    return {shape(std::move(difference)), 0.1, {}};
  }
  if (name == "cylinder_graded") {
    // Three times finer on the axis than at the wall: h = 1 + 2 r, graded by the distance to a
    // hair-thin cylinder along the axis.
    SizeField3 size;
    size.terms.push_back(DistanceSize3{shape(Cylinder{{0, 0, -2}, 1e-9, 4.0}), 1.0, 2.0, 3.0});
    return {shape(Cylinder{{0, 0, -1}, 1.0, 2.0}, "cylinder"), 0.05, std::move(size)};
  }
  if (name == "torus") return {shape(Torus{{0, 0, 0}, 1.0, 0.4}, "torus"), 0.08, {}};
  throw Error(ErrorCode::kInvalidArgument, "domain", "must be one of " + case3d_names());
}

std::string case3d_names() { return "ball, box_minus_sphere, cylinder_graded, torus"; }

}  // namespace meshd::bench
