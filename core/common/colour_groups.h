// Nodes in groups of which no two share an element, so that a group's nodes can move at once,
// each changing only its own star (the worst-element optimisations in 2D and 3D).
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

namespace meshd {

// `nodes` (increasing) in groups: each node, in order, takes the first group that none of its
// neighbours already took, so the groups depend on the nodes alone, not on any thread count.
// star_nodes(v, visit) calls visit(u) for every node u of every element around v.
template <typename StarNodes>
std::vector<std::vector<int32_t>> colour_groups(const std::vector<int32_t>& nodes,
                                                StarNodes&& star_nodes) {
  // Indexed by node (only `nodes` get one), -1 for none yet: an array, not a hash map, because
  // the finish's smoothing colours most of a million-node mesh.
  const int32_t last = nodes.empty() ? -1 : *std::max_element(nodes.begin(), nodes.end());
  std::vector<int32_t> colour(static_cast<size_t>(last + 1), -1);
  std::vector<std::vector<int32_t>> groups;
  std::vector<char> taken;
  for (int32_t v : nodes) {
    taken.assign(groups.size() + 1, 0);
    star_nodes(v, [&](int32_t u) {
      if (static_cast<size_t>(u) < colour.size() && colour[u] >= 0) taken[colour[u]] = 1;
    });
    const auto c = static_cast<int32_t>(std::find(taken.begin(), taken.end(), 0) - taken.begin());
    if (c == static_cast<int32_t>(groups.size())) groups.emplace_back();
    groups[c].push_back(v);
    colour[v] = c;
  }
  return groups;
}

}  // namespace meshd
