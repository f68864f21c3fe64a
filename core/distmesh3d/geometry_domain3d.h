// A Domain3 (domain3d.h) made from a 3D geometry tree: the compiled program's distance, its box,
// its sharp features as fixed nodes, and its primitives' names as boundary groups.
#pragma once

#include <cmath>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/distmesh3d/domain3d.h"
#include "core/geometry3d/program3d.h"
#include "core/geometry3d/shape3d.h"
#include "core/geometry3d/size_field3.h"

namespace meshd {

// How far from the boundary, in the largest edge lengths, the loop needs the distance exact:
// no node moves, and no pit or sliver search looks, that far in one step.
constexpr double kExactDistanceEdges = 4.0;

class GeometryDomain3 {
 public:
  // The domain of a compiled `program`, its sharp edges sampled about h0 times the size field's
  // smallest value along them apart. size: the relative edge length h(p) > 0, or empty for a
  // uniform field. h0 > 0 in the request's length unit. sharp_features false: no fixed nodes
  // (the sharp edges are rounded at about h0). exact_band: the distance is exact within it of
  // the boundary and at least it beyond (with the right sign), which spares a polyhedron's far
  // points most of its triangles; infinite: exact everywhere.
  GeometryDomain3(std::shared_ptr<const Program3> program, double h0,
                  std::function<double(Vec3)> size, bool sharp_features, double exact_band);
  // The same, compiling `shape` first (throws Error naming the field for a bad one).
  GeometryDomain3(const Shape3& shape, double h0, std::function<double(Vec3)> size = {},
                  bool sharp_features = true, double exact_band = INFINITY);
  // The same with a compiled size field (kept alive here), which a GPU engine can evaluate;
  // `uniform`: the field has no terms (h = 1).
  GeometryDomain3(std::shared_ptr<const Program3> program, double h0,
                  std::shared_ptr<const CompiledSizeField3> size_field, bool uniform,
                  bool sharp_features, double exact_band);
  // The domain's callables point into this object.
  GeometryDomain3(const GeometryDomain3&) = delete;
  GeometryDomain3& operator=(const GeometryDomain3&) = delete;

  const Domain3& domain() const { return domain_; }
  const Program3& program() const { return *program_; }

 private:
  std::shared_ptr<const Program3> program_;
  std::shared_ptr<const CompiledSizeField3> size_field_;
  std::vector<int> group_of_primitive_;  // #P: index into domain_.boundary_names
  Domain3 domain_;
};

}  // namespace meshd
