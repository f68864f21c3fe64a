// Delaunay triangulation by parallel point insertion and flipping (the scheme of the GPU builders
// gDel2D and its successors), one element's share of each step, for the host and the device.
//
// The points start inside one enclosing triangle. An insertion step lets every triangle that
// holds uninserted points take one of them, the nearest to its centroid: the point splits its
// triangle in three, or, when it lies exactly on an edge, both triangles of that edge in two
// each. Flip steps follow until no edge certainly fails the in-circle test: each candidate edge
// votes for its two triangles, the smallest edge id winning both. After each step the changed
// triangles link their neighbours again and the points they held find their new triangle among
// the ones that took the old one's place. Every choice is a minimum over unique keys and every
// new slot comes from a prefix sum, so the result is the same on the host and the device, run
// after run.
//
// Point location is exact (exact_orientation.cuh), so every triangle stays counter-clockwise
// and a point on an edge splits that edge. The flips here act only on certain in-circle tests:
// the caller finishes with an exact Lawson repair, after dropping the enclosing triangle's
// corners and completing the convex hull (parallel_insertion.h).
#pragma once

#include <cstdint>
#include <cstring>

#include "core/common/hd.h"
#include "core/common/vec2.h"
#include "core/delaunay/exact_orientation.cuh"
#include "core/delaunay/filtered_predicates.cuh"
#include "core/delaunay/tri.cuh"

namespace meshd {

// An empty vote.
constexpr unsigned long long kNoVote = ~0ull;

struct InsertionState {
  const Vec2* p;  // the n points, then the three corners of the enclosing triangle
  int32_t n;
  Tri* tris;  // room for 2 n + 1 triangles (every point and corner in, 2 (n + 3) - 5)
  Tri* nbrs;
  int32_t* loc;  // #n: the triangle holding point i, -1 once inserted or found a duplicate
  int8_t* edge;  // #n: the edge of loc[i] (the slot opposite it) that i lies on, -1 inside
  unsigned long long* vote;  // per triangle
  int32_t* family;           // per triangle, 2: the slots that took a share of its area
  int32_t* stamp;            // per triangle: the step that last changed it
  int32_t* flips;            // a flip step's flips
  int32_t* lost;             // points that found no triangle (none, unless a bug)
};

// The enclosing triangle of the points in the box [lo, hi]: a right triangle, counter-clockwise,
// whose legs lie at least 64 box widths (a power of two) from the box's centre. The farther its
// corners, the fewer hull triangles their circles swallow (the completion restores those).
MESHD_HD inline void enclosing_triangle(Vec2 lo, Vec2 hi, Vec2 corners[3]) {
  const double cx = 0.5 * (lo.x + hi.x), cy = 0.5 * (lo.y + hi.y);
  double half = fmax(hi.x - lo.x, hi.y - lo.y);
  if (!(half > 0.0)) half = fmax(1.0, fmax(fabs(cx), fabs(cy)));
  int exponent = 0;
  frexp(half, &exponent);
  const double k = ldexp(1.0, exponent + 6);
  corners[0] = {cx - k, cy - k};
  corners[1] = {cx + 3.0 * k, cy - k};
  corners[2] = {cx - k, cy + 3.0 * k};
}

namespace insertion_detail {

MESHD_HD inline void vote_min(unsigned long long* slot, unsigned long long value) {
#ifdef __CUDA_ARCH__
  atomicMin(slot, value);
#else
  if (value < *slot) *slot = value;
#endif
}

MESHD_HD inline void count_one(int32_t* counter) {
#ifdef __CUDA_ARCH__
  atomicAdd(counter, 1);
#else
  ++*counter;
#endif
}

MESHD_HD inline int next(int k) { return k == 2 ? 0 : k + 1; }
MESHD_HD inline int prev(int k) { return k == 0 ? 2 : k - 1; }

// The slot of triangle t's corners that is neither a nor b.
MESHD_HD inline int slot_without(const Tri& t, int32_t a, int32_t b) {
  for (int k = 0; k < 3; ++k)
    if (t.v[k] != a && t.v[k] != b) return k;
  return 0;
}

MESHD_HD inline bool holds_edge(const Tri& t, int32_t a, int32_t b) {
  int found = 0;
  for (int k = 0; k < 3; ++k) found += (t.v[k] == a) + (t.v[k] == b);
  return found == 2;
}

// The quadrilateral across edge k of triangle t = (a, b, c), k the slot of a: the neighbour u =
// (d, c, b) and the four outer neighbours, each named by its edge.
struct Quad {
  int32_t a, b, c, d, u;
  int32_t n_ab, n_ca, n_bd, n_dc;
};
MESHD_HD inline Quad quad_across(const InsertionState& s, int32_t t, int k) {
  const Tri tv = s.tris[t], tn = s.nbrs[t];
  Quad q;
  q.a = tv.v[k];
  q.b = tv.v[next(k)];
  q.c = tv.v[prev(k)];
  q.n_ab = tn.v[prev(k)];
  q.n_ca = tn.v[next(k)];
  q.u = tn.v[k];
  const Tri uv = s.tris[q.u], un = s.nbrs[q.u];
  const int j = slot_of(un, t);
  q.d = uv.v[j];
  q.n_bd = un.v[next(j)];
  q.n_dc = un.v[prev(j)];
  return q;
}

// Triangle x's old area now lies in x and `other` alone.
MESHD_HD inline void share_area(const InsertionState& s, int32_t x, int32_t other) {
  s.family[2 * x] = other;
  s.family[2 * x + 1] = -1;
}

}  // namespace insertion_detail

// Point i's claim on its triangle: the squared distance to the triangle's centroid, or for a
// point on an edge to the edge's midpoint, as float bits (ordered as integers for non-negative
// floats) above the point's index. A run of collinear points on one edge (a lattice's row on the
// hull, under a far corner's centroid) then splits at its middle, and takes a logarithmic number
// of steps rather than one point a step from its end.
MESHD_HD inline unsigned long long insertion_key(const InsertionState& s, int32_t i) {
  const Tri t = s.tris[s.loc[i]];
  double cx, cy;
  if (s.edge[i] >= 0) {
    const Vec2 a = s.p[t.v[insertion_detail::next(s.edge[i])]];
    const Vec2 b = s.p[t.v[insertion_detail::prev(s.edge[i])]];
    cx = 0.5 * (a.x + b.x);
    cy = 0.5 * (a.y + b.y);
  } else {
    const Vec2 a = s.p[t.v[0]], b = s.p[t.v[1]], c = s.p[t.v[2]];
    cx = (a.x + b.x + c.x) / 3.0;
    cy = (a.y + b.y + c.y) / 3.0;
  }
  const double dx = s.p[i].x - cx, dy = s.p[i].y - cy;
  const float d2 = static_cast<float>(dx * dx + dy * dy);
  unsigned int bits;
  memcpy(&bits, &d2, sizeof bits);
  return (static_cast<unsigned long long>(bits) << 32) | static_cast<uint32_t>(i);
}

// Step 1 of an insertion: uninserted point i votes for its triangle (both, on an edge).
MESHD_HD inline void vote_for_point(const InsertionState& s, int32_t i) {
  const int32_t t = s.loc[i];
  if (t < 0) return;
  const unsigned long long key = insertion_key(s, i);
  insertion_detail::vote_min(&s.vote[t], key);
  if (s.edge[i] >= 0) insertion_detail::vote_min(&s.vote[s.nbrs[t].v[s.edge[i]]], key);
}

// Step 2: whether point i won every triangle it voted for.
MESHD_HD inline bool point_wins(const InsertionState& s, int32_t i) {
  const int32_t t = s.loc[i];
  if (t < 0 || static_cast<uint32_t>(s.vote[t]) != static_cast<uint32_t>(i)) return false;
  if (s.edge[i] < 0) return true;
  return static_cast<uint32_t>(s.vote[s.nbrs[t].v[s.edge[i]]]) == static_cast<uint32_t>(i);
}

// Step 3: the winner i splits its triangle (new slots `fresh` and fresh + 1), or the two of its
// edge. The outer neighbours keep their old slots until relink_triangle.
MESHD_HD inline void insert_point(const InsertionState& s, int32_t i, int32_t fresh, int32_t step) {
  const int32_t t = s.loc[i];
  const int32_t s1 = fresh, s2 = fresh + 1;
  const Tri tv = s.tris[t], tn = s.nbrs[t];
  s.loc[i] = -1;
  if (s.edge[i] < 0) {
    const int32_t a = tv.v[0], b = tv.v[1], c = tv.v[2];
    s.tris[t] = Tri{{i, b, c}};
    s.nbrs[t] = Tri{{tn.v[0], s1, s2}};
    s.tris[s1] = Tri{{a, i, c}};
    s.nbrs[s1] = Tri{{t, tn.v[1], s2}};
    s.tris[s2] = Tri{{a, b, i}};
    s.nbrs[s2] = Tri{{t, s1, tn.v[2]}};
    s.family[2 * t] = s1;
    s.family[2 * t + 1] = s2;
    s.stamp[t] = s.stamp[s1] = s.stamp[s2] = step;
    return;
  }
  // i on edge b-c of t = (a, b, c); u = (d, c, b) across it.
  const insertion_detail::Quad q = insertion_detail::quad_across(s, t, s.edge[i]);
  const int32_t u = q.u;
  s.tris[t] = Tri{{q.a, q.b, i}};
  s.nbrs[t] = Tri{{s2, s1, q.n_ab}};
  s.tris[s1] = Tri{{q.a, i, q.c}};
  s.nbrs[s1] = Tri{{u, q.n_ca, t}};
  s.tris[u] = Tri{{q.d, q.c, i}};
  s.nbrs[u] = Tri{{s1, s2, q.n_dc}};
  s.tris[s2] = Tri{{q.d, i, q.b}};
  s.nbrs[s2] = Tri{{t, q.n_bd, u}};
  insertion_detail::share_area(s, t, s1);
  insertion_detail::share_area(s, u, s2);
  s.stamp[t] = s.stamp[s1] = s.stamp[u] = s.stamp[s2] = step;
}

// After an insertion or flip step, for a triangle x it changed: each neighbour slot that still
// names a triangle the step replaced is pointed at the member of that triangle's family that
// holds the shared edge, and an unchanged neighbour is pointed back at x.
MESHD_HD inline void relink_triangle(const InsertionState& s, int32_t x, int32_t step) {
  using insertion_detail::holds_edge;
  using insertion_detail::next;
  using insertion_detail::prev;
  const Tri xv = s.tris[x];
  for (int k = 0; k < 3; ++k) {
    const int32_t y = s.nbrs[x].v[k];
    if (y < 0) continue;
    const int32_t e0 = xv.v[next(k)], e1 = xv.v[prev(k)];
    if (s.stamp[y] != step) {
      s.nbrs[y].v[insertion_detail::slot_without(s.tris[y], e0, e1)] = x;
      continue;
    }
    int32_t found = y;
    if (!holds_edge(s.tris[y], e0, e1)) {
      const int32_t f0 = s.family[2 * y], f1 = s.family[2 * y + 1];
      found = (f0 >= 0 && holds_edge(s.tris[f0], e0, e1)) ? f0 : f1;
    }
    s.nbrs[x].v[k] = found;
  }
}

// Where point i lies in triangle x: -3 on a corner (a twin of a point already in), -2 outside,
// -1 strictly inside, else the slot of the edge it lies on.
MESHD_HD inline int place_in(const InsertionState& s, int32_t i, int32_t x) {
  const Tri t = s.tris[x];
  int on = -1, zeros = 0;
  for (int k = 0; k < 3; ++k) {
    const int side = orientation_exact(s.p[t.v[insertion_detail::next(k)]],
                                       s.p[t.v[insertion_detail::prev(k)]], s.p[i]);
    if (side < 0) return -2;
    if (side == 0) {
      on = k;
      ++zeros;
    }
  }
  return zeros == 2 ? -3 : on;
}

// After a step, an uninserted point whose triangle the step changed looks for itself among the
// triangles that took its area; one that lands on a corner is a duplicate and leaves. Counts a
// failure (none holds it) in s.lost.
MESHD_HD inline void relocate_point(const InsertionState& s, int32_t i, int32_t step) {
  const int32_t t = s.loc[i];
  if (t < 0 || s.stamp[t] != step) return;
  const int32_t candidates[3] = {t, s.family[2 * t], s.family[2 * t + 1]};
  for (int32_t x : candidates) {
    if (x < 0) continue;
    const int where = place_in(s, i, x);
    if (where == -2) continue;
    s.loc[i] = where == -3 ? -1 : x;  // a twin stays out, as delaunay.h keeps duplicates out
    s.edge[i] = static_cast<int8_t>(where);
    return;
  }
  insertion_detail::count_one(s.lost);
}

// An edge's rank in a flip step's votes: its id hashed with the step's number. Ranked by id alone,
// a chain of candidate edges flips one edge a step from its low end (a lattice's rows of
// co-circular points cascaded through thousands of steps); ranked at random, about a third of
// every chain flips each step.
MESHD_HD inline unsigned long long flip_priority(uint32_t id, int32_t step) {
  uint32_t h = id * 0x9e3779b1u ^ static_cast<uint32_t>(step) * 0x85ebca6bu;
  h ^= h >> 16;
  h *= 0x7feb352du;
  h ^= h >> 15;
  h *= 0x846ca68bu;
  h ^= h >> 16;
  return h;
}

// A flip step's vote: each edge of t shared with a later triangle u, where either changed at or
// after step `since`, votes for both when u's far corner is certainly inside t's circle.
MESHD_HD inline void vote_for_flips(const InsertionState& s, int32_t t, int32_t since,
                                    int32_t step) {
  const Tri tv = s.tris[t];
  for (int k = 0; k < 3; ++k) {
    const int32_t u = s.nbrs[t].v[k];
    if (u <= t) continue;
    if (s.stamp[t] < since && s.stamp[u] < since) continue;
    const int32_t d = s.tris[u].v[slot_of(s.nbrs[u], t)];
    if (in_circle_filtered(s.p[tv.v[0]], s.p[tv.v[1]], s.p[tv.v[2]], s.p[d]) <= 0) continue;
    const uint32_t id = 3u * static_cast<uint32_t>(t) + static_cast<uint32_t>(k);
    const unsigned long long key = flip_priority(id, step) << 32 | id;
    insertion_detail::vote_min(&s.vote[t], key);
    insertion_detail::vote_min(&s.vote[u], key);
  }
}

// Whether the flips after an insertion step may stop with candidates left: once a step flips
// fewer than 1/32 of the first step's flips. A cascade's tail flips a few edges a step for
// dozens of steps (a lattice's collinear runs); point location does not need it settled. The
// next insertion's flips test everything changed since the unsettled ones began, and the flips
// after the last insertion run until none is left.
inline bool flips_may_wait(int64_t first_step_flips, int64_t step_flips) {
  return step_flips * 32 < first_step_flips;
}

// The flip itself, by the triangle t that owns an edge winning both its triangles: t = (a, b, c)
// and u = (d, c, b) become (a, b, d) and (a, d, c). Counts the flip in s.flips.
MESHD_HD inline void flip_won_edge(const InsertionState& s, int32_t t, int32_t step) {
  const unsigned long long key = s.vote[t];
  const uint32_t id = static_cast<uint32_t>(key);
  if (key == kNoVote || id / 3 != static_cast<uint32_t>(t)) return;
  const int k = static_cast<int>(id % 3);
  const int32_t u = s.nbrs[t].v[k];
  if (s.vote[u] != key) return;
  const insertion_detail::Quad q = insertion_detail::quad_across(s, t, k);
  s.tris[t] = Tri{{q.a, q.b, q.d}};
  s.nbrs[t] = Tri{{q.n_bd, u, q.n_ab}};
  s.tris[u] = Tri{{q.a, q.d, q.c}};
  s.nbrs[u] = Tri{{q.n_dc, q.n_ca, t}};
  insertion_detail::share_area(s, t, u);
  insertion_detail::share_area(s, u, t);
  s.stamp[t] = s.stamp[u] = step;
  insertion_detail::count_one(s.flips);
}

}  // namespace meshd
