// The tetrahedra around each node (its star), as one flat array, and what the 3D finish's node
// moves ask of stars (the surface settling and the sliver optimisation).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/common/colour_groups.h"
#include "core/common/vec3.h"

namespace meshd {

struct TetStars {
  // #N + 1: node v's tetrahedra are tets[first[v] .. first[v + 1]), increasing.
  std::vector<int64_t> first;
  std::vector<int32_t> tets;

  // tets: #M by 4 indices in [0, nodes) (not checked).
  TetStars(size_t nodes, const std::vector<std::array<int32_t, 4>>& mesh_tets)
      : first(nodes + 1, 0) {
    for (const auto& t : mesh_tets)
      for (int32_t v : t) ++first[v + 1];
    for (size_t v = 0; v < nodes; ++v) first[v + 1] += first[v];
    tets.resize(first.back());
    std::vector<int64_t> next(first.begin(), first.end() - 1);
    for (size_t t = 0; t < mesh_tets.size(); ++t)
      for (int32_t v : mesh_tets[t]) tets[next[v]++] = static_cast<int32_t>(t);
  }

  // Calls fn(t) for each tetrahedron around v.
  template <typename Fn>
  void for_each(int32_t v, Fn&& fn) const {
    for (int64_t k = first[v]; k < first[v + 1]; ++k) fn(tets[k]);
  }
  int64_t size(int32_t v) const { return first[v + 1] - first[v]; }

  // `nodes` (increasing) in groups of which no two share a tetrahedron (colour_groups.h).
  std::vector<std::vector<int32_t>> colour_groups(
      const std::vector<int32_t>& nodes,
      const std::vector<std::array<int32_t, 4>>& mesh_tets) const {
    return meshd::colour_groups(nodes, [&](int32_t v, auto&& visit) {
      for_each(v, [&](int32_t t) {
        for (int32_t u : mesh_tets[t]) visit(u);
      });
    });
  }

  // The mean length of the edges from v to the other nodes of its tetrahedra (each edge counted
  // once per tetrahedron), 0 for a node with none.
  double mean_edge(int32_t v, const std::vector<Vec3>& points,
                   const std::vector<std::array<int32_t, 4>>& mesh_tets) const {
    double sum = 0.0;
    int count = 0;
    for_each(v, [&](int32_t t) {
      for (int32_t u : mesh_tets[t]) {
        if (u == v) continue;
        sum += norm(points[u] - points[v]);
        ++count;
      }
    });
    return count > 0 ? sum / count : 0.0;
  }
};

}  // namespace meshd
