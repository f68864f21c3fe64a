// A set of points that answers "is any within `gap` of p?": how the sharp features keep one of
// several candidates at a corner, and the crease points keep their distance from the rest.
#pragma once

#include <cmath>
#include <cstddef>
#include <functional>
#include <unordered_map>
#include <vector>

#include "core/common/vec3.h"

namespace meshd {

// A hash grid of cells `gap` wide. Cell coordinates stay doubles: coordinates up to 1e150 over a
// tiny gap overflow any integer type.
class SpacedPoints3 {
 public:
  explicit SpacedPoints3(double gap) : gap_(gap) {}

  // Whether some point of the set lies within gap of p (at gap included).
  bool near(Vec3 p) const {
    const Cell c = cell(p);
    for (double dx = -1; dx <= 1; ++dx)
      for (double dy = -1; dy <= 1; ++dy)
        for (double dz = -1; dz <= 1; ++dz) {
          const auto it = cells_.find({c.x + dx, c.y + dy, c.z + dz});
          if (it == cells_.end()) continue;
          for (Vec3 q : it->second)
            if (norm(q - p) <= gap_) return true;
        }
    return false;
  }

  void add(Vec3 p) { cells_[cell(p)].push_back(p); }

 private:
  struct Cell {
    double x, y, z;
    bool operator==(const Cell&) const = default;
  };
  struct CellHash {
    size_t operator()(const Cell& c) const {
      const std::hash<double> h;
      return h(c.x) ^ (h(c.y) * 0x9e3779b97f4a7c15ull) ^ (h(c.z) * 0xc2b2ae3d27d4eb4full);
    }
  };
  Cell cell(Vec3 p) const {
    return {std::floor(p.x / gap_), std::floor(p.y / gap_), std::floor(p.z / gap_)};
  }

  double gap_;
  std::unordered_map<Cell, std::vector<Vec3>, CellHash> cells_;
};

}  // namespace meshd
