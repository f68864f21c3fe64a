// The triangles around chosen nodes (their stars), found when asked for.
//
// The worst-element optimisation needs the stars of the few nodes it moves, near the few
// triangles under its threshold; a table of every node's star cost a large mesh more than the
// optimisation (at 8M triangles, 100 MB written in an order no cache follows). Here each request
// scans the triangles once, in parallel, for the nodes it names.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace meshd {

class ThreadPool;

class StarTable {
 public:
  StarTable(size_t nodes, const std::vector<std::array<int32_t, 3>>& triangles, ThreadPool* pool);

  // Finds the stars of those `nodes` that have none yet, in one scan of the triangles.
  void add(const std::vector<int32_t>& nodes);

  bool has(int32_t v) const { return slot_[v] >= 0; }
  // v's triangles, increasing; v must have a star (add).
  const int32_t* begin(int32_t v) const { return tri_.data() + first_[slot_[v]]; }
  const int32_t* end(int32_t v) const { return tri_.data() + first_[slot_[v] + 1]; }

 private:
  const std::vector<std::array<int32_t, 3>>& t_;
  ThreadPool* pool_;
  std::vector<int32_t> slot_;   // #N: the node's index into first_, -1 without a star
  std::vector<int32_t> first_;  // per node with a star, where its triangles start in tri_; + end
  std::vector<int32_t> tri_;
};

}  // namespace meshd
