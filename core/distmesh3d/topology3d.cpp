#include "core/distmesh3d/topology3d.h"

#include <algorithm>

#include "core/delaunay/delaunay3d.h"

namespace meshd {
namespace {

constexpr size_t kChunk = 4096;
using Face = std::array<int32_t, 3>;

Face sorted_face(const std::array<int32_t, 4>& t, int skip) {
  Face f{};
  int k = 0;
  for (int i = 0; i < 4; ++i)
    if (i != skip) f[k++] = t[i];
  std::sort(f.begin(), f.end());
  return f;
}

// The faces used by one tetrahedron of `tets` (the surface of their union), sorted.
std::vector<Face> surface_faces(const std::vector<std::array<int32_t, 4>>& tets) {
  std::vector<Face> faces;
  faces.reserve(4 * tets.size());
  for (const auto& t : tets)
    for (int i = 0; i < 4; ++i) faces.push_back(sorted_face(t, i));
  std::sort(faces.begin(), faces.end());
  std::vector<Face> once;
  for (size_t i = 0; i < faces.size();) {
    size_t j = i;
    while (j < faces.size() && faces[j] == faces[i]) ++j;
    if (j - i == 1) once.push_back(faces[i]);
    i = j;
  }
  return once;
}

// Gives back to `kept` the tetrahedra of `candidates` (dropped by the centroid filter, their
// centroid inside) that lie on the surface at a node deeper than `below` inside the domain:
// the filter drops a tetrahedron with three nodes on the boundary and one a little inside,
// which leaves a pit in the surface whose floor is that node. A few passes, as a tetrahedron
// given back may expose the next.
void fill_pits(const Domain3& domain, const std::vector<Vec3>& points,
               const std::vector<std::array<int32_t, 4>>& candidates, double below,
               std::vector<std::array<int32_t, 4>>& kept) {
  std::vector<char> taken(candidates.size(), 0);
  for (int pass = 0; pass < 4; ++pass) {
    const std::vector<Face> surface = surface_faces(kept);
    std::vector<char> deep(points.size(), 0);
    bool any = false;
    for (const Face& f : surface)
      for (int32_t v : f)
        if (!deep[v] && domain.distance(points[v]) < -below) deep[v] = any = true;
    if (!any) return;
    size_t added = 0;
    for (size_t c = 0; c < candidates.size(); ++c) {
      const auto& t = candidates[c];
      if (taken[c] || !(deep[t[0]] || deep[t[1]] || deep[t[2]] || deep[t[3]])) continue;
      for (int i = 0; i < 4; ++i) {
        if (!std::binary_search(surface.begin(), surface.end(), sorted_face(t, i))) continue;
        kept.push_back(t);
        taken[c] = 1;
        ++added;
        break;
      }
    }
    if (added == 0) return;
  }
}

}  // namespace

Topology3 triangulate3d(const Domain3& domain, const std::vector<Vec3>& points, int64_t fixed,
                        double depth, double coincidence, ThreadPool* pool, double pit_depth) {
  const std::vector<std::array<int32_t, 4>> all = delaunay_tetrahedralize(points);
  Topology3 topology;
  topology.tets = gather_chunks<std::array<int32_t, 4>>(
      pool, all.size(), kChunk, [&](size_t begin, size_t end, auto& kept) {
        for (size_t t = begin; t < end; ++t) {
          const auto& v = all[t];
          const Vec3 centroid = 0.25 * (points[v[0]] + points[v[1]] + points[v[2]] + points[v[3]]);
          if (domain.distance(centroid) < -depth) kept.push_back(v);
        }
      });
  if (pit_depth > 0.0) {
    std::vector<std::array<int32_t, 4>> inside;  // dropped, yet with their centroid inside
    for (const auto& v : all) {
      const double d =
          domain.distance(0.25 * (points[v[0]] + points[v[1]] + points[v[2]] + points[v[3]]));
      if (d < 0.0 && d >= -depth) inside.push_back(v);
    }
    fill_pits(domain, points, inside, pit_depth, topology.tets);
  }
  build_bars3d(topology, static_cast<int64_t>(points.size()));
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

void build_bars3d(Topology3& topology, int64_t nodes) {
  // Each edge in the bucket of its lower end, each bucket sorted and made unique: the global
  // sort's order without its cost (a sort of all 6 M edges took a sixth of a 28k-node run).
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
  auto& bars = topology.bars;
  bars.clear();
  for (int64_t n = 0; n < nodes; ++n) {
    const auto begin = upper.begin() + first[n], end = upper.begin() + first[n + 1];
    std::sort(begin, end);
    for (auto it = begin; it != end; ++it)
      if (it == begin || *it != *(it - 1)) bars.push_back({static_cast<int32_t>(n), *it});
  }

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
