#include "core/distmesh3d/initial_points3d.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "core/common/error.h"
#include "core/distmesh/initial_points.cuh"

namespace meshd {
namespace {

// A lattice point's threshold in [0, 1) for the rejection test: the R3 sequence (steps 2^64 /
// phi^k, phi the root of x^4 = x + 1) over its three lattice indices, shifted by the seed, as
// 2D's dither_threshold does with R2: neighbours get thresholds spread evenly over [0, 1).
double dither_threshold3(uint64_t seed, int64_t i, int64_t j, int64_t k) {
  constexpr uint64_t kStepI = 0xD1B54A32D192ED03ull;
  constexpr uint64_t kStepJ = 0xABC98388FB8FAC02ull;
  constexpr uint64_t kStepK = 0x8CB92BA72F3D8DD7ull;
  const uint64_t t = mix_seed(seed) + static_cast<uint64_t>(i) * kStepI +
                     static_cast<uint64_t>(j) * kStepJ + static_cast<uint64_t>(k) * kStepK;
  return static_cast<double>(t >> 11) * 0x1.0p-53;
}

// A lattice is as degenerate as a point set gets (the eight corners of every cube on one sphere),
// which sends every in-sphere test of the first triangulation to exact arithmetic: moving each
// point by a millionth of the lattice's side, in a direction hashed from its indices, makes the
// first triangulation as fast as the later ones. The forces cannot tell, but the first
// triangulation splits the cubes otherwise, so the relaxation's path (its iteration count) moves.
constexpr double kLatticeJitter = 1e-6;

}  // namespace

double bcc_cube_side(double h0) { return h0 * std::cbrt(std::sqrt(2.0)); }

std::vector<Vec3> initial_points3d(const Domain3& domain, double h0, double geps, uint64_t seed) {
  const double a = bcc_cube_side(h0);
  const Box3& b = domain.bounds;
  const auto count = [&](double lo, double hi) {
    return static_cast<int64_t>(std::floor((hi - lo) / a)) + 1;
  };
  const int64_t nx = count(b.min.x, b.max.x), ny = count(b.min.y, b.max.y),
                nz = count(b.min.z, b.max.z);
  if (static_cast<double>(nx) * static_cast<double>(ny) * static_cast<double>(nz) > 2e9)
    throw Error(ErrorCode::kResourceExhausted, "h0",
                "too many lattice points for the domain's box; raise h0");

  struct Candidate {
    Vec3 p;
    double h;
    double threshold;
  };
  std::vector<Candidate> inside;
  double h_min = INFINITY;
  // Lattice index 2i + s (s = 0 corner, 1 centre) along each axis; centres sit half a side in.
  for (int64_t k = 0; k < 2 * nz - 1; ++k)
    for (int64_t j = 0; j < 2 * ny - 1; ++j)
      for (int64_t i = 0; i < 2 * nx - 1; ++i) {
        if ((i & 1) != (j & 1) || (j & 1) != (k & 1)) continue;  // corners or centres only
        const double jitter = kLatticeJitter * a;
        const Vec3 p{b.min.x + 0.5 * a * static_cast<double>(i) +
                         jitter * (dither_threshold3(seed + 1, i, j, k) - 0.5),
                     b.min.y + 0.5 * a * static_cast<double>(j) +
                         jitter * (dither_threshold3(seed + 2, i, j, k) - 0.5),
                     b.min.z + 0.5 * a * static_cast<double>(k) +
                         jitter * (dither_threshold3(seed + 3, i, j, k) - 0.5)};
        if (!(domain.distance(p) < geps * h0)) continue;
        const double h = domain.size ? domain.size(p) : 1.0;
        h_min = std::min(h_min, h);
        inside.push_back({p, h, dither_threshold3(seed, i, j, k)});
      }

  // The fixed nodes in buckets a crowding distance wide, so that each candidate looks at the
  // 27 around its own.
  double h_max = 0.0;
  for (const Candidate& c : inside) h_max = std::max(h_max, c.h);
  const double cell = std::max(0.5 * h0 * h_max, 1e-300);
  const auto key = [&](Vec3 p, int dx, int dy, int dz) {
    const auto index = [&](double v, double lo, int d) {
      return static_cast<int64_t>(std::floor((v - lo) / cell)) + d + 2;
    };
    // Fixed nodes lie on the boundary, within the box; 2^21 buckets an axis is plenty.
    return (index(p.x, b.min.x, dx) << 42) | (index(p.y, b.min.y, dy) << 21) |
           index(p.z, b.min.z, dz);
  };
  std::unordered_map<int64_t, std::vector<int32_t>> buckets;
  for (size_t f = 0; f < domain.fixed.size(); ++f)
    buckets[key(domain.fixed[f], 0, 0, 0)].push_back(static_cast<int32_t>(f));
  const auto crowded = [&](Vec3 p, double near) {
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const auto it = buckets.find(key(p, dx, dy, dz));
          if (it == buckets.end()) continue;
          for (int32_t f : it->second)
            if (norm(p - domain.fixed[f]) < near) return true;
        }
    return false;
  };

  std::vector<Vec3> points = domain.fixed;
  for (const Candidate& c : inside) {
    const double ratio = h_min / c.h;
    if (!(c.threshold < ratio * ratio * ratio)) continue;
    // A node closer to a fixed one than half its size would only make a sliver with it.
    if (!crowded(c.p, 0.5 * h0 * c.h)) points.push_back(c.p);
  }
  return points;
}

}  // namespace meshd
