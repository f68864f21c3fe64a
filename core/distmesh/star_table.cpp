#include "core/distmesh/star_table.h"

#include "core/common/thread_pool.h"

namespace meshd {
namespace {
constexpr size_t kTrianglesPerChunk = 1 << 15;
}  // namespace

StarTable::StarTable(size_t nodes, const std::vector<std::array<int32_t, 3>>& triangles,
                     ThreadPool* pool)
    : t_(triangles), pool_(pool), slot_(nodes, -1), first_(1, 0) {}

void StarTable::add(const std::vector<int32_t>& nodes) {
  const auto before = static_cast<int32_t>(first_.size()) - 1;
  int32_t added = 0;
  for (int32_t v : nodes)
    if (slot_[v] < 0) slot_[v] = before + added++;
  if (added == 0) return;
  // The (new slot, triangle) pairs come in triangle order (gather_chunks joins the chunks in
  // order), so every star gets its triangles in increasing order, for any number of threads.
  using Entry = std::array<int32_t, 2>;  // new slot, triangle
  const std::vector<Entry> found = gather_chunks<Entry>(
      pool_, t_.size(), kTrianglesPerChunk, [&](size_t begin, size_t end, std::vector<Entry>& out) {
        for (size_t t = begin; t < end; ++t)
          for (int32_t v : t_[t])
            if (slot_[v] >= before) out.push_back({slot_[v], static_cast<int32_t>(t)});
      });
  std::vector<int32_t> count(added + 1, 0);
  for (const Entry& e : found) ++count[e[0] - before + 1];
  const int32_t base = first_.back();
  for (int32_t k = 0; k < added; ++k) {
    count[k + 1] += count[k];
    first_.push_back(base + count[k + 1]);
  }
  tri_.resize(first_.back());
  for (const Entry& e : found) tri_[base + count[e[0] - before]++] = e[1];
}

}  // namespace meshd
