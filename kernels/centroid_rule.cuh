// The centroid filter's rule (DistMesh's step 3): a triangle is kept where its centroid lies
// inside by more than geps, decided by its nodes' clearances where they can (clearance.cuh), else
// by the distance there. The filter's kernel (topology.cu) and a small triangulation's bars'
// launch (bars_in_one_block.cu) share it.
#pragma once

#include "core/geometry/sdf_eval.cuh"
#include "kernels/launch.h"

namespace meshd::gpu {

__device__ inline bool centroid_kept(const CentroidFilter& f, DeviceSpan<const Vec2> p,
                                     const Tri& tri) {
  const Vec2 v[3] = {p[tri.v[0]], p[tri.v[1]], p[tri.v[2]]};
  const float c[3] = {f.clearance[tri.v[0]], f.clearance[tri.v[1]], f.clearance[tri.v[2]]};
  const Vec2 centroid = (1.0 / 3.0) * (v[0] + v[1] + v[2]);
  return f.clear.centroid_inside(c, v, centroid) ||
         eval_sdf(f.fd, centroid, f.nested_index) < -f.geps;
}

}  // namespace meshd::gpu
