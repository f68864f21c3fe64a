#include "core/distmesh3d/surface_offset3d.h"

#include <algorithm>
#include <cmath>

#include "core/mesh3d/tet_boundary.h"

namespace meshd {

SurfaceOffset3 surface_offset3d(const Domain3& domain, const std::vector<Vec3>& points,
                                const std::vector<std::array<int32_t, 3>>& boundary_faces,
                                double tolerance) {
  std::vector<char> on_surface(points.size(), 0);
  for (const auto& f : boundary_faces)
    for (int32_t v : f) on_surface[v] = 1;
  SurfaceOffset3 out;
  for (size_t v = 0; v < points.size(); ++v) {
    if (!on_surface[v]) continue;
    const double offset = std::fabs(domain.distance(points[v]));
    ++out.surface;
    out.max = std::max(out.max, offset);
    if (offset > tolerance) ++out.beyond;
  }
  return out;
}

SurfaceOffset3 surface_offset3d(const Domain3& domain, const std::vector<Vec3>& points,
                                const std::vector<std::array<int32_t, 4>>& tets, double tolerance) {
  return surface_offset3d(domain, points, tet_boundary_faces(tets), tolerance);
}

}  // namespace meshd
