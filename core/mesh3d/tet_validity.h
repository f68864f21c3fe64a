// Checks that a tetrahedral mesh keeps the invariants stated in tet_mesh.h, and reports every
// kind of defect, as validity.h does for triangles.
//
// A report is meant for people (a failing test, a log line, an INTERNAL error's message) and for
// tests that want to know which check fired: problems holds one line per kind of defect, naming
// the first offender by index, and the num_* counters say how many there were.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/mesh3d/tet_mesh.h"

namespace meshd {

// A tetrahedron counts as degenerate when 6 V <= tolerance * (longest edge)^3: relative to the
// longest edge so that the test does not depend on the length unit. 1e-12 rejects turned-over
// tetrahedra and round-off zeros but accepts any sliver that is really there (the regular
// tetrahedron has 6 V / longest^3 = 0.71; a flat sliver with q = 1e-4 still has about 3e-5).
constexpr double kDefaultVolumeTolerance = 1e-12;

// 6 V / (longest edge)^3 of the tetrahedron abcd: 0.71 for the regular one, negative when it is
// turned over, 0 when two corners coincide, NaN when all four do or a coordinate is not finite.
double relative_six_volume(Vec3 a, Vec3 b, Vec3 c, Vec3 d);

// Whether abcd is turned over or degenerate by check_tet_validity's rule (NaN included), so that
// an engine can drop what the check would refuse. Flat by a radius ratio near 0 is not the same:
// four corners nearly on a line (samples along a straight edge) keep q about as large as
// 6 V / longest^3, where four nearly on a plane have q about its square.
inline bool degenerate_tet(Vec3 a, Vec3 b, Vec3 c, Vec3 d,
                           double volume_tolerance = kDefaultVolumeTolerance) {
  return !(relative_six_volume(a, b, c, d) > volume_tolerance);
}

struct TetValidityReport {
  // One human-readable line per kind of defect; empty when the mesh is valid.
  std::vector<std::string> problems;

  // Sizes, for the log.
  int64_t num_points = 0;
  int64_t num_tets = 0;
  int64_t num_boundary_faces = 0;  // faces used by one tetrahedron
  int64_t num_interior_faces = 0;  // faces used by two tetrahedra in opposite turns

  // Defects; all zero in a valid mesh.
  int64_t num_nonfinite_points = 0;         // NaN or infinite coordinates
  int64_t num_bad_indices = 0;              // tetrahedra or boundary faces outside [0, #N)
  int64_t num_inverted = 0;                 // negatively oriented or degenerate tetrahedra
  int64_t first_inverted = -1;              // index of the first of them, -1 when none
  int64_t num_nonconforming_faces = 0;      // used by 3+ tetrahedra, or by 2 in the same turn
  int64_t num_unused_points = 0;            // points no tetrahedron uses
  int64_t num_missing_boundary_faces = 0;   // one-tetrahedron faces absent from boundary_faces
  int64_t num_reversed_boundary_faces = 0;  // listed turned inward
  int64_t num_extra_boundary_faces = 0;     // listed but not a one-tetrahedron face, or twice
  int64_t num_bad_tags = 0;                 // tags outside boundary_names, or #tags != #faces
  int64_t num_bad_names = 0;                // empty or repeated boundary group names

  bool valid() const { return problems.empty(); }
};

// Checks every invariant of tet_mesh.h: coordinates finite, indices in range, tetrahedra
// positively oriented with a volume above the tolerance, every face used by one tetrahedron
// (boundary) or by two in opposite turns (conforming), every point used, boundary_faces exactly
// the one-tetrahedron faces turned outward (as the tetrahedron has them, up to rotation), tags in
// range of boundary_names, names non-empty and distinct. Never throws on a bad mesh;
// O(#M log #M).
//
// mesh: the mesh to check.
// volume_tolerance: dimensionless, >= 0; see kDefaultVolumeTolerance.
TetValidityReport check_tet_validity(const TetMesh& mesh,
                                     double volume_tolerance = kDefaultVolumeTolerance);

// The sum of the tetrahedra's signed volumes, in the cube of the mesh's length unit.
// Tetrahedra with out-of-range indices are skipped.
double mesh_volume(const TetMesh& mesh);

// The cheap part of check_tet_validity that writers need before they index arrays with the
// mesh's numbers: tetrahedron and boundary-face indices in [0, #N), one tag per boundary face,
// tags in [0, #boundary_names). Throws Error(kInternal, field "mesh") naming the first offender.
void check_indices(const TetMesh& mesh);

}  // namespace meshd
