#include "core/distmesh/trapped_nodes.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "core/delaunay/exact_predicates.h"
#include "core/mesh/boundary.h"

namespace meshd {
namespace {

// A removal takes one triangle from each neighbour's star, which can leave a neighbour trapped
// in turn; each pass removes trapped nodes of which no two share a triangle.
constexpr int kMaxPasses = 8;

class TrappedNodes {
 public:
  TrappedNodes(MeshCopy& mesh, int32_t nfix)
      : m_(mesh),
        t_(mesh.triangles),
        nfix_(nfix),
        boundary_ends_(half_edge_ends(mesh.triangles, mesh.boundary)),
        on_boundary_(mesh.points.size(), 0) {
    for (const auto& e : boundary_ends_) on_boundary_[e[0]] = on_boundary_[e[1]] = 1;
  }

  int64_t run() {
    int64_t removed = 0;
    for (int pass = 0; pass < kMaxPasses; ++pass) {
      const int64_t now = remove_pass();
      if (now == 0) break;
      removed += now;
    }
    if (removed > 0) renumber();
    return removed;
  }

 private:
  using Star = std::array<int32_t, 3>;

  int64_t remove_pass() {
    // Valences in bytes, saturating (a fixed corner may have hundreds of triangles): the count
    // over every triangle is the pass's whole cost when, as in most meshes, no node is trapped.
    const size_t n = m_.points.size();
    std::vector<uint8_t> valence(n, 0);
    for (size_t s = 0; s < t_.size(); ++s) {
      if (!merged_into_.empty() && merged_into_[s] >= 0) continue;
      for (int32_t v : t_[s]) valence[v] += valence[v] < UINT8_MAX;
    }
    std::vector<int32_t> centres;
    for (size_t v = nfix_; v < n; ++v)
      if (valence[v] == 3 && !on_boundary_[v]) centres.push_back(static_cast<int32_t>(v));
    if (centres.empty()) return 0;
    std::vector<int32_t> slot(n, -1);
    for (size_t k = 0; k < centres.size(); ++k) slot[centres[k]] = static_cast<int32_t>(k);
    if (merged_into_.empty()) merged_into_.assign(t_.size(), -1);
    std::vector<Star> stars(centres.size());
    std::vector<int> filled(centres.size(), 0);
    for (size_t s = 0; s < t_.size(); ++s) {
      if (merged_into_[s] >= 0) continue;
      for (int32_t v : t_[s])
        if (slot[v] >= 0) stars[slot[v]][filled[slot[v]]++] = static_cast<int32_t>(s);
    }
    // A node is removed unless a neighbour was, this pass: then their stars shared triangles.
    std::vector<char> taken(n, 0);
    int64_t removed = 0;
    for (size_t k = 0; k < stars.size(); ++k) {
      const int32_t v = centres[k];
      bool neighbour_taken = false;
      for (int32_t s : stars[k])
        for (int32_t u : t_[s]) neighbour_taken |= taken[u] != 0;
      if (neighbour_taken || !merge(v, stars[k])) continue;
      taken[v] = 1;
      ++removed;
    }
    return removed;
  }

  // Replaces v's star by its outer triangle; false (nothing changed) unless the star is a fan of
  // three triangles turned alike, around v strictly inside the outer one.
  bool merge(int32_t v, const Star& star) {
    const std::vector<Vec2>& p = m_.points;
    const auto& first = t_[star[0]];
    const int i = first[0] == v ? 0 : (first[1] == v ? 1 : 2);
    const int32_t a = first[(i + 1) % 3], b = first[(i + 2) % 3];
    int32_t c = -1;
    for (int j = 1; j < 3; ++j) {
      int32_t other = -1;
      for (int32_t u : t_[star[j]])
        if (u != v && u != a && u != b) other = u;
      if (other < 0 || (c >= 0 && other != c)) return false;
      c = other;
    }
    const int sense = orientation_sign(p[v], p[a], p[b]);
    if (sense == 0 || orientation_sign(p[v], p[b], p[c]) != sense ||
        orientation_sign(p[v], p[c], p[a]) != sense)
      return false;
    for (int j = 1; j < 3; ++j) {
      const auto& tri = t_[star[j]];
      if (orientation_sign(p[tri[0]], p[tri[1]], p[tri[2]]) != sense) return false;
    }
    t_[star[0]] = {a, b, c};
    merged_into_[star[1]] = merged_into_[star[2]] = star[0];
    survivors_.push_back(star[0]);
    return true;
  }

  int32_t final_of(int32_t s) const {
    while (merged_into_[s] >= 0) s = merged_into_[s];
    return s;
  }

  // Drops the merged triangles, renumbering the rest in order, and carries the boundary's
  // half-edges and the optimisation's starting triangles over to the new numbers.
  void renumber() {
    std::vector<int32_t> new_index(t_.size(), -1);
    std::vector<std::array<int32_t, 3>> kept;
    kept.reserve(t_.size());
    for (size_t s = 0; s < t_.size(); ++s) {
      if (merged_into_[s] >= 0) continue;
      new_index[s] = static_cast<int32_t>(kept.size());
      kept.push_back(t_[s]);
    }
    // An outer edge of a star keeps its direction in the star's new triangle (turned alike).
    std::vector<int32_t> boundary;
    boundary.reserve(m_.boundary.size());
    for (size_t e = 0; e < m_.boundary.size(); ++e) {
      const int32_t s = final_of(m_.boundary[e] / 3);
      const auto& tri = t_[s];
      const auto& [from, to] = boundary_ends_[e];
      int k = 0;
      while (k < 3 && !(tri[k] == from && tri[(k + 1) % 3] == to)) ++k;
      if (k == 3) throw std::logic_error("remove_trapped_nodes: a boundary edge was lost");
      boundary.push_back(3 * new_index[s] + k);
    }
    std::sort(boundary.begin(), boundary.end());
    if (m_.below) {
      std::vector<int32_t> below;
      for (int32_t s : *m_.below) below.push_back(new_index[final_of(s)]);
      for (int32_t s : survivors_)
        if (merged_into_[s] < 0) below.push_back(new_index[s]);
      std::sort(below.begin(), below.end());
      below.erase(std::unique(below.begin(), below.end()), below.end());
      *m_.below = std::move(below);
    }
    t_ = std::move(kept);
    m_.boundary = std::move(boundary);
    m_.tidy = false;
  }

  MeshCopy& m_;
  std::vector<std::array<int32_t, 3>>& t_;
  int32_t nfix_;
  std::vector<std::array<int32_t, 2>> boundary_ends_;
  std::vector<char> on_boundary_;
  // -1 while the triangle lives; empty until a pass finds a trapped node.
  std::vector<int32_t> merged_into_;
  std::vector<int32_t> survivors_;  // the triangles a merge rewrote
};

}  // namespace

int64_t remove_trapped_nodes(MeshCopy& mesh, int32_t nfix) {
  if (mesh.none_trapped) return 0;
  return TrappedNodes(mesh, nfix).run();
}

}  // namespace meshd
