// Checks that a mesh keeps the invariants stated in mesh.h, and reports every kind of defect.
//
// A report is meant for people (a failing test, a log line, an INTERNAL error's message) and for
// tests that want to know which check fired: problems holds one line per kind of defect, naming
// the first offender by index, and the num_* counters say how many there were.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/mesh/mesh.h"

namespace meshd {

// A triangle counts as degenerate when 2 * area <= tolerance * (longest edge)^2. Relative to the
// longest edge so that the test does not depend on the length unit. 1e-12 rejects inverted
// triangles and round-off zeros but accepts any sliver that is really there (an equilateral
// triangle has 2 area / longest^2 = 0.87; one with a 1e-6 degree angle still has about 1e-8).
constexpr double kDefaultAreaTolerance = 1e-12;

struct ValidityReport {
  // One human-readable line per kind of defect; empty when the mesh is valid.
  std::vector<std::string> problems;

  // Sizes, for the log.
  int64_t num_points = 0;
  int64_t num_triangles = 0;
  int64_t num_boundary_edges = 0;  // edges used by one triangle
  int64_t num_interior_edges = 0;  // edges used by two triangles with opposite orientation

  // Defects; all zero in a valid mesh.
  int64_t num_nonfinite_points = 0;         // NaN or infinite coordinates
  int64_t num_bad_indices = 0;              // triangles or boundary edges outside [0, #N)
  int64_t num_inverted = 0;                 // clockwise or degenerate triangles
  int64_t first_inverted = -1;              // index of the first of them, -1 when none
  int64_t num_nonconforming_edges = 0;      // used by 3+ triangles, or by 2 in one direction
  int64_t num_unused_points = 0;            // points no triangle uses
  int64_t num_missing_boundary_edges = 0;   // one-triangle edges absent from boundary_edges
  int64_t num_reversed_boundary_edges = 0;  // listed with the domain on the right
  int64_t num_extra_boundary_edges = 0;     // listed but not a one-triangle edge, or listed twice
  int64_t num_bad_tags = 0;                 // tags outside boundary_names, or #tags != #edges
  int64_t num_bad_names = 0;                // empty or repeated boundary group names

  bool valid() const { return problems.empty(); }
};

// Checks every invariant of mesh.h: coordinates finite, indices in range, triangles
// counter-clockwise with positive area, every edge used by one triangle (boundary) or by two in
// opposite directions (conforming), every point used, boundary_edges exactly the one-triangle
// edges with the domain on their left, tags in range of boundary_names, names non-empty and
// distinct. Never throws on a bad mesh; O(#M log #M).
//
// mesh: the mesh to check.
// area_tolerance: dimensionless, >= 0; see kDefaultAreaTolerance.
ValidityReport check_validity(const Mesh& mesh, double area_tolerance = kDefaultAreaTolerance);

// The sum of the triangles' signed areas, in the square of the mesh's length unit. Triangles
// with out-of-range indices are skipped.
double mesh_area(const Mesh& mesh);

// The cheap part of check_validity that writers need before they index arrays with the mesh's
// numbers: triangle and boundary-edge indices in [0, #N), one tag per boundary edge, tags in
// [0, #boundary_names). Throws Error(kInternal, field "mesh") naming the first offender.
void check_indices(const Mesh& mesh);

}  // namespace meshd
