// Delaunay tetrahedralization of a point set through CGAL (exact predicates), returned as arrays.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "core/common/vec3.h"

namespace meshd {

// The finite Delaunay tetrahedra of `points` (#N by 3), #M by 4 point indices, each positively
// oriented: (b - a) . ((c - a) x (d - a)) > 0. Of points that coincide, only the lowest index
// appears in the tetrahedra.
// Cospherical points are split by CGAL's symbolic perturbation, so the tetrahedra depend only on
// the points, not on the order of insertion: with `threads` > 1 (and a build with TBB) CGAL
// inserts large sets in parallel, and the result, each tetrahedron starting at its lowest index
// and the list sorted, is the same for any thread count.
std::vector<std::array<int32_t, 4>> delaunay_tetrahedralize(const std::vector<Vec3>& points,
                                                            unsigned threads = 1);

// The same, kept between calls, so that a few points that moved need not rebuild the rest: each
// moves by removal and reinsertion (CGAL's move). The result is then the Delaunay tetrahedra of
// the points as last built or moved, those of `moved` at their new places and the others where
// they were, which is what DistMesh's loop asks between two full triangulations.
class Tetrahedralization3 {
 public:
  Tetrahedralization3();
  ~Tetrahedralization3();
  Tetrahedralization3(const Tetrahedralization3&) = delete;
  Tetrahedralization3& operator=(const Tetrahedralization3&) = delete;

  // delaunay_tetrahedralize(points, threads), kept.
  std::vector<std::array<int32_t, 4>> build(const std::vector<Vec3>& points, unsigned threads);
  // Moves the points `moved` (indices into the last build's points, which `points` must number
  // the same) to their places in `points`. Nothing (and the triangulation is gone, to be built
  // again) when a point lands on another or the last build had coinciding points.
  std::optional<std::vector<std::array<int32_t, 4>>> move(const std::vector<Vec3>& points,
                                                          const std::vector<int32_t>& moved);
  // Takes the points `gone` (indices, increasing) out and numbers the rest as a compaction that
  // keeps their order does (remove_nodes3d), so that later moves and builds continue from there.
  // False (and the triangulation is gone) when the last build had coinciding points.
  bool remove(const std::vector<int32_t>& gone);
  // Drops the triangulation, whose points were moved elsewhere (a repair on the device): later
  // moves and removals answer nothing until the next build.
  void forget();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace meshd
