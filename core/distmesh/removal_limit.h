// How many nodes a density check or a clean-up round may remove at once, in the plane loop
// (distmesh.cpp) and the volume loop (distmesh3d.cpp) alike.
#pragma once

#include <cstdint>

namespace meshd {

// A removal of more than this share of the free nodes at once is not meeting a local excess: the
// L0 scale is skewed (in a domain a few edges thick long sliver bars inflate it; so does an
// fscale near the top of its range), and the removal would empty the mesh (tests/fuzz/
// FINDINGS.md: a coarse torus lost every node at its first density check). It is skipped.
constexpr double kMaxRemovedShare = 0.25;

// The most nodes one removal may take from `free_nodes` free (not fixed) nodes.
inline int64_t most_removed_at_once(int64_t free_nodes) {
  return static_cast<int64_t>(kMaxRemovedShare * static_cast<double>(free_nodes));
}

}  // namespace meshd
