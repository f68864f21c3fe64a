#include "core/distmesh/corner_clusters.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <unordered_map>

#include "core/geometry/sdf_eval.cuh"
#include "core/geometry/size_eval.cuh"

namespace meshd {
namespace {

// Points with a reach each, found again by "which lie within min(their reach, r) of p". One hash
// grid per power of two of the reach, its cells at least as large as the reaches it holds, so
// that a query scans 3 x 3 cells per level however the reaches vary along a graded outline.
class ReachGrid {
 public:
  explicit ReachGrid(size_t expected) { cells_.reserve(expected); }

  void add(size_t id, Vec2 p, double reach) {
    const int level = std::ilogb(reach) + 1;
    if (std::find(levels_.begin(), levels_.end(), level) == levels_.end()) levels_.push_back(level);
    cells_[cell_of(p, level)].push_back({id, p, reach});
  }

  // Whether a point q other than `except` lies within min(reach, q's reach) of p.
  bool any_near(Vec2 p, double reach, size_t except) const {
    for (int level : levels_) {
      const Cell c = cell_of(p, level);
      for (int64_t dx = -1; dx <= 1; ++dx)
        for (int64_t dy = -1; dy <= 1; ++dy) {
          const auto it = cells_.find({c.x + dx, c.y + dy, level});
          if (it == cells_.end()) continue;
          for (const Entry& e : it->second)
            if (e.id != except && norm(p - e.p) < std::min(reach, e.reach)) return true;
        }
    }
    return false;
  }

 private:
  struct Entry {
    size_t id;
    Vec2 p;
    double reach;
  };
  struct Cell {
    int64_t x, y;
    int level;
    bool operator==(const Cell&) const = default;
  };
  struct CellHash {
    size_t operator()(const Cell& c) const {
      return std::hash<int64_t>()((c.x * 0x9E3779B97F4A7C15ull ^ c.y) * 31 + c.level);
    }
  };
  // Cells of side 2^level, which holds the reaches in [2^(level - 1), 2^level).
  static Cell cell_of(Vec2 p, int level) {
    const double side = std::ldexp(1.0, level);
    auto index = [side](double v) {
      return static_cast<int64_t>(std::clamp(std::floor(v / side), -4e18, 4e18));
    };
    return {index(p.x), index(p.y), level};
  }

  std::vector<int> levels_;
  std::unordered_map<Cell, std::vector<Entry>, CellHash> cells_;
};

// |pi - the domain's angle at c|: the share of a small circle around c that lies inside.
double sharpness(ProgramView geometry, Vec2 c, double radius) {
  constexpr int kSamples = 24;  // 15 degrees apart: enough to rank
  int inside = 0;
  for (int k = 0; k < kSamples; ++k) {
    const double a = 2.0 * std::numbers::pi * (k + 0.5) / kSamples;
    if (eval_sdf(geometry, c + radius * Vec2{std::cos(a), std::sin(a)}) < 0.0) ++inside;
  }
  return std::fabs(std::numbers::pi - 2.0 * std::numbers::pi * inside / kSamples);
}

}  // namespace

std::vector<Vec2> thin_corner_clusters(const std::vector<Vec2>& corners,
                                       const std::vector<double>& turns,
                                       const std::vector<Vec2>& kept, const Program& geometry,
                                       const SizeProgram& size, double h0) {
  const SizeView field = size.view();
  auto reach_at = [&](Vec2 p) { return kCornerClusterShare * h0 * eval_size(field, p); };
  std::vector<double> reach(corners.size());
  for (size_t i = 0; i < corners.size(); ++i) reach[i] = reach_at(corners[i]);

  // Which corners have another (or a kept point) within reach: only those can be dropped.
  const size_t none = corners.size();
  ReachGrid all(corners.size() + kept.size());
  for (size_t i = 0; i < corners.size(); ++i) all.add(i, corners[i], reach[i]);
  for (Vec2 p : kept) all.add(none, p, reach_at(p));
  std::vector<size_t> crowded;
  for (size_t i = 0; i < corners.size(); ++i)
    if (all.any_near(corners[i], reach[i], i)) crowded.push_back(i);
  if (crowded.empty()) return corners;

  // The crowded corners, sharpest first, each kept unless a kept one is within reach.
  std::vector<double> sharp(corners.size(), 0.0);
  for (size_t i : crowded)
    sharp[i] =
        std::isnan(turns[i]) ? sharpness(geometry.view(), corners[i], 1e-3 * reach[i]) : turns[i];
  std::stable_sort(crowded.begin(), crowded.end(),
                   [&](size_t a, size_t b) { return sharp[a] > sharp[b]; });
  std::vector<char> keep(corners.size(), 1);
  ReachGrid taken(crowded.size() + kept.size());
  for (Vec2 p : kept) taken.add(none, p, reach_at(p));
  for (size_t i : crowded) keep[i] = 0;
  for (size_t i : crowded) {
    if (taken.any_near(corners[i], reach[i], SIZE_MAX)) continue;
    keep[i] = 1;
    taken.add(i, corners[i], reach[i]);
  }
  std::vector<Vec2> out;
  for (size_t i = 0; i < corners.size(); ++i)
    if (keep[i]) out.push_back(corners[i]);
  return out;
}

}  // namespace meshd
