// The repair of a kept Delaunay tetrahedralization by flips once its points moved
// (flip_rounds3.cuh has the rounds), on the host: the reference that the device's repair
// (kernels/flip_repair3.h) answers the same tetrahedra as, and the tests' way to the rounds
// without a GPU.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/common/vec3.h"
#include "core/delaunay/flip_rounds3.cuh"

namespace meshd {

// Rounds a repair runs at most: a DistMesh retriangulation's flips settle in a few dozen.
constexpr int kRepairRounds3 = 200;

// A repair ends when a round finds no flip to make. What it leaves may still hold tetrahedra
// that are flat or turned over, faces that fail but that no flip can take (a stuck star,
// gDel3D's case), and, where flips ran beside turned tetrahedra, a face made twice. On a curved
// boundary nodes that slide past each other turn the flat tetrahedra of four boundary nodes
// over, which only flips of the hull's faces could mend. The caller judges whether what is left
// matters (the DistMesh loop keeps only tetrahedra whose centroid lies inside, and asks that
// each of those be positive).
struct RepairOutcome3 {
  bool ended = false;  // a round found no flip (false: out of rounds or of slots)
  int rounds = 0;
  int64_t flips = 0;
  int64_t inverted = 0;  // tetrahedra left flat or turned over
  int64_t stuck = 0;     // failing faces left
  int64_t overfull = 0;  // faces in more than two tetrahedra
  // The tetrahedra conform (each face in one or two): what the DistMesh loop can check further.
  bool usable() const { return ended && overfull == 0; }
  bool clean() const { return usable() && inverted == 0 && stuck == 0; }
};

// Room for the 2-3 flips' new slots beside m tetrahedra: a repair's net growth is a few per
// cent, and the slots that 3-2 flips leave dead are not reused.
inline int64_t flip_capacity3(int64_t m) { return m + m / 4 + 4096; }

// The outcome of a repair whose last round (`last`, of `rounds`) flipped nothing, or that ran
// out of rounds or slots (`ended` false), with `overfull` faces in more than two tetrahedra.
RepairOutcome3 repair_outcome3(const FlipCounts3& last, bool ended, int rounds, int64_t flips,
                               int64_t overfull);

// How many of the sorted face keys `keys` (n) are the third or later of their key.
int64_t overfull_faces(const uint64_t* keys, int64_t n);

// Takes out of `tets` those not positively oriented for certain (filtered_predicates3.cuh),
// keeping the others' order, and returns them.
std::vector<std::array<int32_t, 4>> take_turned3(const std::vector<Vec3>& points,
                                                 std::vector<std::array<int32_t, 4>>& tets);

class FlipRepair3 {
 public:
  // Keeps `tets` (all of a Delaunay tetrahedralization of `nodes` points, positively oriented)
  // and links each face to its neighbour's. False, keeping nothing, where the point numbers do
  // not fit a face's key (2^21 points and more).
  bool keep(const std::vector<std::array<int32_t, 4>>& tets, int64_t nodes);
  // Repairs the kept tetrahedra for `points` (numbered as at keep). The triangulation is
  // forgotten unless the outcome is usable.
  RepairOutcome3 repair(const std::vector<Vec3>& points, int max_rounds = kRepairRounds3);
  // The live tetrahedra, in slot order.
  std::vector<std::array<int32_t, 4>> tets() const;

 private:
  std::vector<Tet4> tets_;
  std::vector<int32_t> adj_, third_, position_;
  std::vector<uint32_t> claim_;
  std::vector<uint8_t> turned_, kind_, new_slot_;
  int64_t slots_ = 0;
  bool kept_ = false;
};

}  // namespace meshd
