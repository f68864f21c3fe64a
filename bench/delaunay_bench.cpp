// delaunay_bench: the GPU engine's Delaunay builder (point insertion on the device, its hull
// completed and flipped with exact predicates) against CGAL on the host's CPU, on the same point
// sets; prints one table row per set and size for RESULTS.md.
//
//   delaunay_bench [--repeat R] N...
//
// Sets: uniform (random in the unit square), clustered (Gaussian clusters of very different
// spreads), lattice (a triangular lattice, every row collinear and every cell co-circular,
// jittered by nothing). The device's time runs from the points on the device to the linked
// triangles there (best of R); CGAL's is delaunay_triangulate's (best of R). Each row checks that
// both give the same triangles where the triangulation is unique.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "core/delaunay/delaunay.h"
#include "kernels/gpu_engine.h"

namespace {

using meshd::Vec2;

std::vector<Vec2> point_set(const std::string& kind, int64_t n) {
  std::mt19937_64 rng(42);
  std::vector<Vec2> p;
  p.reserve(n);
  if (kind == "uniform") {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int64_t i = 0; i < n; ++i) p.push_back({u(rng), u(rng)});
  } else if (kind == "clustered") {
    std::normal_distribution<double> g(0.0, 1.0);
    const int64_t each = 1000;
    for (int64_t c = 0; static_cast<int64_t>(p.size()) < n; ++c) {
      const Vec2 centre{100.0 * g(rng), 100.0 * g(rng)};
      const double spread = std::ldexp(1.0, -static_cast<int>(rng() % 12));
      for (int64_t k = 0; k < each && static_cast<int64_t>(p.size()) < n; ++k)
        p.push_back({centre.x + spread * g(rng), centre.y + spread * g(rng)});
    }
  } else {
    const auto side = static_cast<int64_t>(std::sqrt(static_cast<double>(n)));
    for (int64_t r = 0; r < side; ++r)
      for (int64_t i = 0; i < side; ++i) p.push_back({i + 0.5 * (r % 2), r * std::sqrt(3.0) / 2});
    std::shuffle(p.begin(), p.end(), rng);
  }
  return p;
}

std::set<std::array<int32_t, 3>> triangle_set(const meshd::Triangulation& t) {
  std::set<std::array<int32_t, 3>> out;
  for (auto v : t.triangles) {
    std::rotate(v.begin(), std::min_element(v.begin(), v.end()), v.end());
    out.insert(v);
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  int repeat = 3;
  std::vector<int64_t> sizes;
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    if (arg == "--repeat" && a + 1 < argc) {
      repeat = std::max(1, std::atoi(argv[++a]));
    } else if (arg == "-h" || arg == "--help") {
      std::printf("usage: delaunay_bench [--repeat R] N...\n");
      return 0;
    } else {
      sizes.push_back(std::atoll(arg.c_str()));
    }
  }
  if (sizes.empty()) sizes = {1000000, 4000000};
  if (meshd::gpu_device_count() == 0) {
    std::fprintf(stderr, "delaunay_bench: no CUDA device visible\n");
    return 1;
  }
  meshd::GpuEngine engine;
  engine.delaunay(point_set("uniform", 1000));  // modules loaded, buffers allocated
  std::printf(
      "| points | set | CGAL s | device s | CGAL / device | insertion steps | flip steps | same "
      "triangles |\n");
  std::printf("|---|---|---|---|---|---|---|---|\n");
  for (const int64_t n : sizes) {
    for (const char* kind : {"uniform", "clustered", "lattice"}) {
      const std::vector<Vec2> p = point_set(kind, n);
      double cgal = 1e30, device = 1e30;
      meshd::Triangulation reference, result;
      meshd::GpuEngine::DelaunayTiming timing;
      for (int r = 0; r < repeat; ++r) {
        const auto t0 = std::chrono::steady_clock::now();
        reference = meshd::delaunay_triangulate(p);
        cgal = std::min(
            cgal, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
        result = engine.delaunay(p, &timing);
        device = std::min(device, timing.seconds);
      }
      // A lattice's co-circular cells have two Delaunay diagonals each: count only there.
      const bool unique = std::string(kind) != "lattice";
      const bool same = unique ? triangle_set(result) == triangle_set(reference)
                               : result.triangles.size() == reference.triangles.size();
      std::printf("| %lld | %s | %.3f | %.4f | %.1f | %d | %d | %s |\n",
                  static_cast<long long>(p.size()), kind, cgal, device, cgal / device,
                  timing.insertion_steps, timing.flip_steps,
                  same ? (unique ? "yes" : "same count") : "NO");
      std::fflush(stdout);
    }
  }
  return 0;
}
