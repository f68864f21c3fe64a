// The quality of a tetrahedral mesh: the radius ratio q = 3 r_in / R_circ (tet_quality.cuh) and
// the dihedral angles, summarised as the 2D report is (quality.h).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/common/vec3.h"
#include "core/mesh/quality.h"
#include "core/mesh3d/tet_mesh.h"
#include "core/mesh3d/tet_quality.cuh"

namespace meshd {

struct TetQualityStats {
  double q_min = 0.0;  // negative when a tetrahedron is turned over
  double q_mean = 0.0;
  double min_dihedral_deg = 0.0;  // over all six angles of every tetrahedron, degrees
  double max_dihedral_deg = 0.0;
  double volume = 0.0;  // the sum of the tetrahedra's signed volumes, request length unit cubed
  // The largest distance of a surface node from the domain's boundary, which the mesh alone does
  // not know: set by generate_mesh3d (surface_offset3d.h), 0 from summarize_tet_quality.
  double max_surface_offset = 0.0;
  // histogram[k] counts tetrahedra with q in [k/10, (k+1)/10); q = 1 lands in the last bin, a
  // turned-over or flat one (q <= 0) in the first.
  std::array<int64_t, kQualityBins> histogram{};
};

// Per-tetrahedron radius ratio (oriented_tet_radius_ratio), #M.
// points: #N by 3; tets: #M by 4 indices in [0, #N) (not checked).
std::vector<double> tet_quality(const std::vector<Vec3>& points,
                                const std::vector<std::array<int32_t, 4>>& tets);
std::vector<double> tet_quality(const TetMesh& mesh);

// q_min, q_mean, the histogram, the dihedral range and the volume over all tetrahedra; all zero
// when there are none. points: #N by 3; tets: #M by 4 indices in [0, #N) (not checked). The
// form on arrays serves the DistMesh loop before its result becomes a TetMesh.
TetQualityStats summarize_tet_quality(const std::vector<Vec3>& points,
                                      const std::vector<std::array<int32_t, 4>>& tets);
TetQualityStats summarize_tet_quality(const TetMesh& mesh);

}  // namespace meshd
