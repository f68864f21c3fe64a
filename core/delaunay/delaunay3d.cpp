#include "core/delaunay/delaunay3d.h"

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Delaunay_triangulation_cell_base_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_data_structure_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>
#include <tbb/parallel_sort.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <unordered_map>
#include <utility>

namespace meshd {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_3<int32_t, Kernel>;
// The concurrent data structure serves the sequential operations too: without a lock grid,
// CGAL inserts and moves one point at a time.
using Tds = CGAL::Triangulation_data_structure_3<
    VertexBase, CGAL::Delaunay_triangulation_cell_base_3<Kernel>, CGAL::Parallel_tag>;
using Delaunay = CGAL::Delaunay_triangulation_3<Kernel, Tds>;
// Below this many points one thread is as fast as several (the locks' overhead).
constexpr size_t kParallelPoints = 20000;
// Cells per axis of the grid of locks over the points' box (CGAL's example's value).
constexpr int kLockGridCells = 50;

// CGAL keeps one vertex for points that coincide, whichever its insertion order met first:
// renumber the tetrahedra to the lowest index of each such set, so that a fixed node (the lowest
// indices) keeps its place when a free node lands on it.
void use_lowest_duplicates(const std::vector<Vec3>& points,
                           std::vector<std::array<int32_t, 4>>& tets) {
  struct Hash {
    size_t operator()(const Vec3& p) const {
      const auto h = [](double v) { return std::hash<double>()(v); };
      return h(p.x) ^ (h(p.y) * 0x9E3779B97F4A7C15ull) ^ (h(p.z) * 0xBF58476D1CE4E5B9ull);
    }
  };
  struct Equal {
    bool operator()(const Vec3& a, const Vec3& b) const { return a == b; }
  };
  std::unordered_map<Vec3, int32_t, Hash, Equal> lowest;
  lowest.reserve(points.size());
  for (size_t i = 0; i < points.size(); ++i) lowest.emplace(points[i], static_cast<int32_t>(i));
  for (auto& t : tets)
    for (int32_t& v : t) v = lowest.at(points[v]);
}

// The finite cells' vertex indices, as CGAL orders them (positively).
template <typename Triangulation>
std::vector<std::array<int32_t, 4>> cells_of(const Triangulation& dt) {
  std::vector<std::array<int32_t, 4>> tets;
  tets.reserve(dt.number_of_finite_cells());
  for (auto c = dt.finite_cells_begin(); c != dt.finite_cells_end(); ++c)
    tets.push_back(
        {c->vertex(0)->info(), c->vertex(1)->info(), c->vertex(2)->info(), c->vertex(3)->info()});
  return tets;
}

// Each tetrahedron turned by an even permutation (which keeps its orientation) to start at its
// lowest index, with the lowest of the other three next; then the list sorted (by the caller's
// TBB arena's threads).
void canonical_order(std::vector<std::array<int32_t, 4>>& tets) {
  for (auto& t : tets) {
    const int lowest = static_cast<int>(std::min_element(t.begin(), t.end()) - t.begin());
    // The even permutation that brings position `lowest` to the front.
    if (lowest == 1) t = {t[1], t[0], t[3], t[2]};
    if (lowest == 2) t = {t[2], t[3], t[0], t[1]};
    if (lowest == 3) t = {t[3], t[2], t[1], t[0]};
    // A rotation of the other three is even too.
    while (t[1] > t[2] || t[1] > t[3]) t = {t[0], t[2], t[3], t[1]};
  }
  tbb::parallel_sort(tets.begin(), tets.end());
}

}  // namespace

struct Tetrahedralization3::Impl {
  Delaunay dt;
  std::vector<Delaunay::Vertex_handle> vertex;  // #N: null for a point on another's place
  bool duplicates = false;
  unsigned threads = 1;

  // The tetrahedra in the order promised, for the points the triangulation holds.
  std::vector<std::array<int32_t, 4>> tets(const std::vector<Vec3>& points) {
    std::vector<std::array<int32_t, 4>> out = cells_of(dt);
    if (duplicates) use_lowest_duplicates(points, out);
    tbb::task_arena arena(static_cast<int>(std::max(1u, threads)));
    arena.execute([&] { canonical_order(out); });
    return out;
  }
};

Tetrahedralization3::Tetrahedralization3() : impl_(std::make_unique<Impl>()) {}
Tetrahedralization3::~Tetrahedralization3() = default;

std::vector<std::array<int32_t, 4>> Tetrahedralization3::build(const std::vector<Vec3>& points,
                                                               unsigned threads) {
  Impl& s = *impl_;
  s.dt.clear();
  s.threads = threads;
  std::vector<std::pair<Kernel::Point_3, int32_t>> input;
  input.reserve(points.size());
  for (size_t i = 0; i < points.size(); ++i)
    input.emplace_back(Kernel::Point_3(points[i].x, points[i].y, points[i].z),
                       static_cast<int32_t>(i));
  if (threads > 1 && points.size() >= kParallelPoints) {
    CGAL::Bbox_3 box = input.front().first.bbox();
    for (const auto& p : input) box += p.first.bbox();
    Delaunay::Lock_data_structure locks(box, kLockGridCells);
    s.dt.set_lock_data_structure(&locks);
    tbb::task_arena arena(static_cast<int>(threads));
    arena.execute([&] { s.dt.insert(input.begin(), input.end()); });
    s.dt.set_lock_data_structure(nullptr);
  } else {
    s.dt.insert(input.begin(), input.end());  // spatially sorted insertion
  }
  s.vertex.assign(points.size(), Delaunay::Vertex_handle());
  for (auto v = s.dt.finite_vertices_begin(); v != s.dt.finite_vertices_end(); ++v)
    s.vertex[v->info()] = v;
  s.duplicates = s.dt.number_of_vertices() < points.size();
  return s.tets(points);
}

std::optional<std::vector<std::array<int32_t, 4>>> Tetrahedralization3::move(
    const std::vector<Vec3>& points, const std::vector<int32_t>& moved) {
  Impl& s = *impl_;
  if (s.duplicates || s.vertex.size() != points.size()) return std::nullopt;
  for (int32_t i : moved) {
    const Delaunay::Vertex_handle v = s.vertex[i];
    const Vec3 p = points[i];
    // CGAL removes v and answers the vertex already there when p is taken.
    if (s.dt.move(v, Kernel::Point_3(p.x, p.y, p.z)) != v) {
      s.dt.clear();
      s.vertex.clear();
      return std::nullopt;
    }
  }
  return s.tets(points);
}

bool Tetrahedralization3::remove(const std::vector<int32_t>& gone) {
  Impl& s = *impl_;
  if (s.duplicates || s.vertex.empty()) {
    s.dt.clear();
    s.vertex.clear();
    return false;
  }
  for (int32_t i : gone) s.dt.remove(s.vertex[i]);
  size_t kept = 0, next_gone = 0;
  for (size_t i = 0; i < s.vertex.size(); ++i) {
    if (next_gone < gone.size() && static_cast<size_t>(gone[next_gone]) == i) {
      ++next_gone;
      continue;
    }
    s.vertex[i]->info() = static_cast<int32_t>(kept);
    s.vertex[kept++] = s.vertex[i];
  }
  s.vertex.resize(kept);
  return true;
}

void Tetrahedralization3::forget() {
  impl_->dt.clear();
  impl_->vertex.clear();
}

std::vector<std::array<int32_t, 4>> delaunay_tetrahedralize(const std::vector<Vec3>& points,
                                                            unsigned threads) {
  return Tetrahedralization3().build(points, threads);
}

}  // namespace meshd
