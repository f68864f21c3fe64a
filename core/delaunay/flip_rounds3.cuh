// One round of the flips that repair a kept tetrahedralization after its points moved, item by
// item, shared by the host's repair (flip_repair3.h) and the device's (kernels/flip_repair3.h),
// which run the same rounds and so answer the same tetrahedra.
//
// Lawson's flips among positive tetrahedra: a face between two tetrahedra that are positive for
// certain fails when the in-sphere test fails for certain. In a round every failing face
// proposes a 2-3 flip (the segment between the two apexes crosses the face) or a 3-2 flip (it
// passes beside one edge, around which there are exactly three tetrahedra), taken only when each
// new tetrahedron is positive for certain. A flip claims its tetrahedra and their outer
// neighbours, the lowest priority (flip_priority) winning each, so that winners touch disjoint
// tetrahedra and the lowest candidate always flips. Orientations and in-sphere tests are filtered
// (filtered_predicates3.cuh): an undecided in-sphere test (points cospherical to rounding) leaves
// its face as it is, which either answer allows. Faces on the hull are never flipped, and
// tetrahedra that the moves turned flat or over (Delaunay tetrahedra of well-spaced points
// include slivers) are counted, not mended; no flip touches them or their neighbours, since the
// tetrahedra there overlap and a flip could make a face that is already there.
//
// Phases of a round, each over every item, the items of a phase independent: mark_turned and
// mark_beside_turned (per slot), propose_flip (per face: 4 slot + f, face f opposite corner f),
// settle_winner (per face), then the new slots numbered by an exclusive scan of new_slot, then
// apply_flip (per face).
#pragma once

#include <cstdint>

#include "core/common/hd.h"
#include "core/common/vec3.h"
#include "core/delaunay/filtered_predicates3.cuh"

namespace meshd {

struct Tet4 {
  int32_t v[4];  // positively oriented (delaunay3d.h); v[0] = -1 in a dead slot
};

// What one round counts.
struct FlipCounts3 {
  int32_t inverted;    // tetrahedra not certainly positive
  int32_t candidates;  // failing faces (between positive tetrahedra)
  int32_t stuck;       // of those, faces that neither flip can take, or beside a turned one
  int32_t undecided;   // in-sphere tests the filter could not decide
  int32_t flips;       // flips the round makes
  int32_t new_slots;   // of those, 2-3 flips (each takes a slot)
  int32_t overfull;    // after the rounds: faces in more than two tetrahedra
};

// The bits of one point number in a face's key: keys of faces with points under 2^21.
constexpr int kFaceKeyBits = 21;

// The arrays of a kept tetrahedralization and of its rounds.
struct FlipArrays3 {
  Tet4* tets;           // the slots
  int32_t* adj;         // per face: the neighbour's face id across it, -1 on the hull
  uint8_t* turned;      // per slot: not certainly positive (kTurned), or beside one
  uint8_t* kind;        // per face: the flip it proposes (kinds below), kWinner once won
  int32_t* third;       // per face: a 3-2 flip's third tetrahedron
  uint32_t* claim;      // per slot: the lowest priority claiming it (all ones before a round)
  uint8_t* new_slot;    // per face: a winning 2-3 flip
  int32_t* position;    // per face: exclusive scan of new_slot
  const Vec3* p;        // the points
  FlipCounts3* counts;  // the round's
};

namespace flip3 {

constexpr uint8_t kWinner = 0x80;
// FlipArrays3::turned's bits.
constexpr uint8_t kTurned = 1;
constexpr uint8_t kBesideTurned = 2;
// A face proposes kFlip23, or kFlip32 + k for the 3-2 flip about the edge from its corner k to
// corner k + 1 (face_corner's order).
constexpr uint8_t kFlip23 = 1;
constexpr uint8_t kFlip32 = 2;

MESHD_HD inline void add_one(int32_t* count) {
#ifdef __CUDA_ARCH__
  atomicAdd(count, 1);
#else
  ++*count;
#endif
}

MESHD_HD inline void claim_lowest(uint32_t* claim, uint32_t priority) {
#ifdef __CUDA_ARCH__
  atomicMin(claim, priority);
#else
  if (priority < *claim) *claim = priority;
#endif
}

// A face's priority in the claims: its id scrambled by an odd multiplier (a bijection of 32-bit
// numbers, so no two faces tie). With the ids themselves, which follow the tetrahedra's spatial
// order, a cluster of failing faces let one flip win at a time.
MESHD_HD inline uint32_t flip_priority(int64_t face) {
  return static_cast<uint32_t>(face) * 0x9E3779B1u;
}

// Corner k of face f (the face opposite v[f]), in an order that puts v[f] on its positive side
// when the tetrahedron is positive.
MESHD_HD inline int face_corner(int f, int k) {
  constexpr int kCorners[4][3] = {{1, 3, 2}, {0, 2, 3}, {0, 3, 1}, {0, 1, 2}};
  return kCorners[f][k];
}

MESHD_HD inline uint64_t face_key(int32_t a, int32_t b, int32_t c) {
  int32_t t;
  if (a > b) t = a, a = b, b = t;
  if (b > c) t = b, b = c, c = t;
  if (a > b) t = a, a = b, b = t;
  return (static_cast<uint64_t>(a) << (2 * kFaceKeyBits)) |
         (static_cast<uint64_t>(b) << kFaceKeyBits) | static_cast<uint64_t>(c);
}

MESHD_HD inline uint64_t face_key_of(const Tet4& t, int f) {
  return face_key(t.v[(f + 1) & 3], t.v[(f + 2) & 3], t.v[(f + 3) & 3]);
}

// Face i's key, or for a dead slot's face one that no other face has (above every live key).
MESHD_HD inline uint64_t slot_face_key(const Tet4& t, int64_t i) {
  if (t.v[0] < 0) return ~uint64_t{0} - static_cast<uint64_t>(i);
  return face_key_of(t, static_cast<int>(i & 3));
}

MESHD_HD inline int corner_of(const Tet4& t, int32_t vertex) {
  for (int k = 0; k < 4; ++k)
    if (t.v[k] == vertex) return k;
  return -1;
}

// The tetrahedra a proposal of face `face` replaces: its own, its neighbour's, and for a 3-2
// flip the third around the edge.
struct Olds {
  int32_t tet[3];
  int n;
  MESHD_HD bool has(int32_t t) const {
    for (int k = 0; k < n; ++k)
      if (tet[k] == t) return true;
    return false;
  }
};

MESHD_HD inline Olds olds_of(const FlipArrays3& a, int64_t face, uint8_t kind) {
  Olds o{{-1, -1, -1}, 0};
  o.tet[0] = static_cast<int32_t>(face >> 2);
  o.tet[1] = a.adj[face] >> 2;
  o.n = 2;
  if (kind >= kFlip32) o.tet[o.n++] = a.third[face];
  return o;
}

}  // namespace flip3

MESHD_HD inline void mark_turned(const FlipArrays3& a, int64_t t) {
  const Tet4 T = a.tets[t];
  const Vec3* p = a.p;
  const bool turned =
      T.v[0] >= 0 && orientation3_filtered(p[T.v[0]], p[T.v[1]], p[T.v[2]], p[T.v[3]]) != 1;
  a.turned[t] = turned ? flip3::kTurned : 0;
  if (turned) flip3::add_one(&a.counts->inverted);
}

// After mark_turned: the neighbours of a turned tetrahedron marked beside it (each writer adds
// the same bit to a value that mark_turned settled, so concurrent writes agree).
MESHD_HD inline void mark_beside_turned(const FlipArrays3& a, int64_t t) {
  if (!(a.turned[t] & flip3::kTurned)) return;
  for (int g = 0; g < 4; ++g) {
    const int32_t nb = a.adj[4 * t + g];
    if (nb >= 0) a.turned[nb >> 2] = a.turned[nb >> 2] | flip3::kBesideTurned;
  }
}

// Face i, once (from its lower slot): when it fails, its flip proposed and its tetrahedra and
// their outer neighbours claimed.
MESHD_HD inline void propose_flip(const FlipArrays3& a, int64_t i) {
  using namespace flip3;
  a.kind[i] = 0;
  const auto t = static_cast<int32_t>(i >> 2);
  const int f = static_cast<int>(i & 3);
  const Tet4 T = a.tets[t];
  const int32_t across = a.adj[i];
  if (T.v[0] < 0 || across < 0 || (across >> 2) <= t) return;
  const int32_t u = across >> 2;
  const Tet4 U = a.tets[u];
  const int32_t e = U.v[across & 3];
  const Vec3* p = a.p;
  if ((a.turned[t] | a.turned[u]) & kTurned) return;
  const int sphere = in_sphere_filtered(p[T.v[0]], p[T.v[1]], p[T.v[2]], p[T.v[3]], p[e]);
  if (sphere == 0) add_one(&a.counts->undecided);
  if (sphere <= 0) return;
  add_one(&a.counts->candidates);
  const int32_t d = T.v[f];
  int32_t c[3];
  for (int k = 0; k < 3; ++k) c[k] = T.v[face_corner(f, k)];
  // New tetrahedron (c[k], c[k + 1], e, d) of a 2-3 flip: positive for all three when the
  // segment from d to e crosses the face.
  int negative = -1, positives = 0;
  for (int k = 0; k < 3; ++k) {
    const int s = orientation3_filtered(p[c[k]], p[c[(k + 1) % 3]], p[e], p[d]);
    positives += s == 1;
    if (s == -1) negative = k;
  }
  uint8_t chosen = 0;
  int32_t m = -1;
  if (positives == 3) {
    chosen = kFlip23;
  } else if (positives == 2 && negative >= 0) {
    // The segment passes beside edge c[k] c[k + 1]: a 3-2 flip when the edge has three
    // tetrahedra, the third being both tetrahedra's neighbour away from c[k + 2].
    const int32_t x = c[negative], y = c[(negative + 1) % 3], z = c[(negative + 2) % 3];
    const int32_t from_t = a.adj[4 * static_cast<int64_t>(t) + corner_of(T, z)];
    const int32_t from_u = a.adj[4 * static_cast<int64_t>(u) + corner_of(U, z)];
    // The new pair (d, z, e, x) and (z, d, e, y): x and y on either side of z d e.
    if (from_t >= 0 && from_u >= 0 && (from_t >> 2) == (from_u >> 2) &&
        orientation3_filtered(p[d], p[z], p[e], p[x]) == 1 &&
        orientation3_filtered(p[z], p[d], p[e], p[y]) == 1) {
      chosen = static_cast<uint8_t>(kFlip32 + negative);
      m = from_t >> 2;
    }
  }
  // A turned tetrahedron near the flip (kTurned or kBesideTurned among its tetrahedra and their
  // outer neighbours): the tetrahedra there overlap, and the flip could make a face that is
  // already there.
  const int32_t olds3[3] = {t, u, m};
  for (int k = 0; k < 3 && chosen != 0; ++k) {
    const int32_t o = olds3[k];
    if (o < 0) continue;
    if (a.turned[o] != 0) chosen = 0;
    for (int g = 0; g < 4; ++g) {
      const int32_t nb = a.adj[4 * static_cast<int64_t>(o) + g];
      if (nb >= 0 && a.turned[nb >> 2] != 0) chosen = 0;
    }
  }
  if (chosen == 0) {
    add_one(&a.counts->stuck);
    return;
  }
  a.kind[i] = chosen;
  a.third[i] = m;
  const Olds olds = olds_of(a, i, chosen);
  const uint32_t id = flip_priority(i);
  for (int k = 0; k < olds.n; ++k) {
    const int32_t o = olds.tet[k];
    claim_lowest(&a.claim[o], id);
    for (int g = 0; g < 4; ++g) {
      const int32_t nb = a.adj[4 * static_cast<int64_t>(o) + g];
      if (nb >= 0 && !olds.has(nb >> 2)) claim_lowest(&a.claim[nb >> 2], id);
    }
  }
}

// Face i's proposal flips when it holds every claim it made; a 2-3 winner asks for a new slot.
MESHD_HD inline void settle_winner(const FlipArrays3& a, int64_t i) {
  using namespace flip3;
  a.new_slot[i] = 0;
  const uint8_t k = a.kind[i];
  if (k == 0) return;
  const Olds olds = olds_of(a, i, k);
  const uint32_t id = flip_priority(i);
  for (int n = 0; n < olds.n; ++n) {
    const int32_t o = olds.tet[n];
    if (a.claim[o] != id) return;
    for (int g = 0; g < 4; ++g) {
      const int32_t nb = a.adj[4 * static_cast<int64_t>(o) + g];
      if (nb >= 0 && !olds.has(nb >> 2) && a.claim[nb >> 2] != id) return;
    }
  }
  a.kind[i] = k | kWinner;
  a.new_slot[i] = k == kFlip23;
  add_one(&a.counts->flips);
  if (k == kFlip23) add_one(&a.counts->new_slots);
}

// Face i's won flip: the new tetrahedra written over the old slots (a 2-3 flip's third at
// `base` + its position), each face linked to the outer neighbour that had the same face, or to
// its sibling; a 3-2 flip's third slot left dead.
MESHD_HD inline void apply_flip(const FlipArrays3& a, int64_t i, int64_t base) {
  using namespace flip3;
  if (!(a.kind[i] & kWinner)) return;
  const uint8_t k = a.kind[i] & ~kWinner;
  const Olds olds = olds_of(a, i, k);
  const int32_t t = olds.tet[0], u = olds.tet[1];
  const int f = static_cast<int>(i & 3);
  const Tet4 T = a.tets[t];
  const int32_t d = T.v[f], e = a.tets[u].v[a.adj[i] & 3];
  int32_t c[3];
  for (int n = 0; n < 3; ++n) c[n] = T.v[face_corner(f, n)];
  // The outer faces (six in either flip), read before any slot is written.
  uint64_t outer_key[6];
  int32_t outer_nb[6];
  int outers = 0;
  for (int n = 0; n < olds.n; ++n) {
    const Tet4 O = a.tets[olds.tet[n]];
    for (int g = 0; g < 4; ++g) {
      const int32_t nb = a.adj[4 * static_cast<int64_t>(olds.tet[n]) + g];
      if ((nb >= 0 && olds.has(nb >> 2)) || outers == 6) continue;
      outer_key[outers] = face_key_of(O, g);
      outer_nb[outers++] = nb;
    }
  }
  Tet4 fresh[3];
  int32_t slot[3] = {t, u, -1};
  int count = 2;
  if (k == kFlip23) {
    for (int n = 0; n < 3; ++n) fresh[n] = Tet4{{c[n], c[(n + 1) % 3], e, d}};
    slot[2] = static_cast<int32_t>(base + a.position[i]);
    count = 3;
  } else {
    const int edge = k - kFlip32;
    const int32_t x = c[edge], y = c[(edge + 1) % 3], z = c[(edge + 2) % 3];
    fresh[0] = Tet4{{d, z, e, x}};
    fresh[1] = Tet4{{z, d, e, y}};
    const int32_t dead = olds.tet[2];
    a.tets[dead] = Tet4{{-1, -1, -1, -1}};
    for (int g = 0; g < 4; ++g) a.adj[4 * static_cast<int64_t>(dead) + g] = -1;
  }
  for (int n = 0; n < count; ++n) a.tets[slot[n]] = fresh[n];
  for (int n = 0; n < count; ++n)
    for (int g = 0; g < 4; ++g) {
      const int64_t face = 4 * static_cast<int64_t>(slot[n]) + g;
      const uint64_t key = face_key_of(fresh[n], g);
      int32_t link = -1;
      bool found = false;
      for (int o = 0; o < outers && !found; ++o)
        if (outer_key[o] == key) {
          link = outer_nb[o];
          found = true;
          if (link >= 0) a.adj[link] = static_cast<int32_t>(face);
        }
      for (int s = 0; s < count && !found; ++s)
        for (int h = 0; h < 4 && s != n && !found; ++h)
          if (face_key_of(fresh[s], h) == key) {
            link = 4 * slot[s] + h;
            found = true;
          }
      a.adj[face] = link;
    }
}

}  // namespace meshd
