// Nodes in groups of which no two share an element, so that a group's nodes can move at once,
// each changing only its own star (the worst-element optimisations in 2D and 3D).
#pragma once

#include <algorithm>
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace meshd {

// `nodes` (increasing) in groups: each node, in order, takes the first group that none of its
// neighbours already took, so the groups depend on the nodes alone, not on any thread count.
// star_nodes(v, visit) calls visit(u) for every node u of every element around v.
template <typename StarNodes>
std::vector<std::vector<int32_t>> colour_groups(const std::vector<int32_t>& nodes,
                                                StarNodes&& star_nodes) {
  std::unordered_map<int32_t, int32_t> colour;
  colour.reserve(nodes.size());
  std::vector<std::vector<int32_t>> groups;
  std::vector<char> taken;
  for (int32_t v : nodes) {
    taken.assign(groups.size() + 1, 0);
    star_nodes(v, [&](int32_t u) {
      const auto it = colour.find(u);
      if (it != colour.end()) taken[it->second] = 1;
    });
    const auto c = static_cast<int32_t>(std::find(taken.begin(), taken.end(), 0) - taken.begin());
    if (c == static_cast<int32_t>(groups.size())) groups.emplace_back();
    groups[c].push_back(v);
    colour[v] = c;
  }
  return groups;
}

}  // namespace meshd
