#include "core/distmesh3d/topology3d.h"

#include <algorithm>

#include "core/delaunay/delaunay3d.h"

namespace meshd {
namespace {

constexpr size_t kChunk = 4096;

}  // namespace

Topology3 triangulate3d(const Domain3& domain, const std::vector<Vec3>& points, int64_t fixed,
                        double depth, double coincidence, ThreadPool* pool) {
  return topology_of3d(domain, points, delaunay_tetrahedralize(points, pool_threads(pool)), fixed,
                       depth, coincidence, pool);
}

unsigned pool_threads(ThreadPool* pool) { return pool != nullptr ? pool->size() : 1; }

Topology3 topology_of3d(const Domain3& domain, const std::vector<Vec3>& points,
                        const std::vector<std::array<int32_t, 4>>& all, int64_t fixed, double depth,
                        double coincidence, ThreadPool* pool) {
  Topology3 topology;
  topology.tets = gather_chunks<std::array<int32_t, 4>>(
      pool, all.size(), kChunk, [&](size_t begin, size_t end, auto& kept) {
        for (size_t t = begin; t < end; ++t) {
          const auto& v = all[t];
          const Vec3 centroid = 0.25 * (points[v[0]] + points[v[1]] + points[v[2]] + points[v[3]]);
          if (domain.distance(centroid) < -depth) kept.push_back(v);
        }
      });
  build_bars3d(topology, static_cast<int64_t>(points.size()), pool);
  // Coincident nodes share an edge of the whole triangulation, kept or not.
  auto& close = topology.coincident;
  close =
      gather_chunks<int32_t>(pool, all.size(), kChunk, [&](size_t begin, size_t end, auto& out) {
        for (size_t t = begin; t < end; ++t)
          for (int a = 0; a < 4; ++a)
            for (int b = a + 1; b < 4; ++b) {
              const int32_t hi = std::max(all[t][a], all[t][b]);
              if (hi >= fixed && norm(points[all[t][a]] - points[all[t][b]]) < coincidence)
                out.push_back(hi);
            }
      });
  std::sort(close.begin(), close.end());
  close.erase(std::unique(close.begin(), close.end()), close.end());
  return topology;
}

void build_bars3d(Topology3& topology, int64_t nodes, ThreadPool* pool) {
  // Each edge in the bucket of its lower end, each bucket sorted and made unique (on the pool's
  // threads): the global sort's order without its cost (a sort of all 6 M edges took a sixth of
  // a 28k-node run).
  std::vector<int64_t> first(static_cast<size_t>(nodes) + 1, 0);
  for (const auto& t : topology.tets)
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b) ++first[std::min(t[a], t[b]) + 1];
  for (int64_t n = 0; n < nodes; ++n) first[n + 1] += first[n];
  std::vector<int32_t> upper(static_cast<size_t>(first[nodes]));
  std::vector<int64_t> fill(first.begin(), first.end() - 1);
  for (const auto& t : topology.tets)
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b) upper[fill[std::min(t[a], t[b])]++] = std::max(t[a], t[b]);
  // fill[n] becomes the end of bucket n's unique part.
  for_chunks(pool, static_cast<size_t>(nodes), kChunk, [&](size_t, size_t begin, size_t end) {
    for (size_t n = begin; n < end; ++n) {
      const auto from = upper.begin() + first[n], to = upper.begin() + first[n + 1];
      std::sort(from, to);
      fill[n] = std::unique(from, to) - upper.begin();
    }
  });
  std::vector<int64_t> bar_of(static_cast<size_t>(nodes) + 1, 0);
  for (int64_t n = 0; n < nodes; ++n) bar_of[n + 1] = bar_of[n] + (fill[n] - first[n]);
  auto& bars = topology.bars;
  bars.resize(static_cast<size_t>(bar_of[nodes]));
  for_chunks(pool, static_cast<size_t>(nodes), kChunk, [&](size_t, size_t begin, size_t end) {
    for (size_t n = begin; n < end; ++n)
      for (int64_t k = first[n]; k < fill[n]; ++k)
        bars[bar_of[n] + (k - first[n])] = {static_cast<int32_t>(n), upper[k]};
  });

  auto& offsets = topology.bar_offsets;
  offsets.assign(static_cast<size_t>(nodes) + 1, 0);
  for (const auto& bar : bars) {
    ++offsets[bar[0] + 1];
    ++offsets[bar[1] + 1];
  }
  for (int64_t n = 0; n < nodes; ++n) offsets[n + 1] += offsets[n];
  topology.bar_ends.resize(2 * bars.size());
  std::vector<int64_t> next(offsets.begin(), offsets.end() - 1);
  for (size_t b = 0; b < bars.size(); ++b) {
    topology.bar_ends[next[bars[b][0]]++] = 2 * static_cast<int64_t>(b);
    topology.bar_ends[next[bars[b][1]]++] = 2 * static_cast<int64_t>(b) + 1;
  }
}

}  // namespace meshd
