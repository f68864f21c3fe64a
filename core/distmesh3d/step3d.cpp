#include "core/distmesh3d/step3d.h"

#include <algorithm>
#include <cmath>

#include "core/distmesh3d/projection3d.h"

namespace meshd {
namespace {

constexpr size_t kChunk = 4096;

}  // namespace

StepResult step3d(const Domain3& domain, const Params3& params, double h0,
                  const Topology3& topology, Nodes3& nodes, BarLengths& bars, ThreadPool* pool) {
  const auto& p = nodes.points;
  const size_t bar_count = topology.bars.size();
  bars.length.resize(bar_count);
  bars.desired.resize(bar_count);
  std::vector<Vec3> push(bar_count);  // the bar's force on its first end, F / L times the bar

  // Step 4: lengths, sizes at the midpoints, and L0 scaled so that the bars' volume matches
  // (distmeshnd: L0 = hbars Fscale (sum L^3 / sum hbars^3)^(1/3)). Partial sums per chunk,
  // added in chunk order: the same bits on any number of threads.
  std::vector<double> sum_l3(ThreadPool::chunk_count(bar_count, kChunk)), sum_h3(sum_l3.size());
  for_chunks(pool, bar_count, kChunk, [&](size_t c, size_t begin, size_t end) {
    double l3 = 0.0, h3 = 0.0;
    for (size_t b = begin; b < end; ++b) {
      const Vec3 a = p[topology.bars[b][0]], e = p[topology.bars[b][1]];
      const double length = norm(a - e);
      const double h = domain.size ? domain.size(0.5 * (a + e)) : 1.0;
      bars.length[b] = length;
      bars.desired[b] = h;
      l3 += length * length * length;
      h3 += h * h * h;
    }
    sum_l3[c] = l3;
    sum_h3[c] = h3;
  });
  double l3 = 0.0, h3 = 0.0;
  for (size_t c = 0; c < sum_l3.size(); ++c) {
    l3 += sum_l3[c];
    h3 += sum_h3[c];
  }
  const double scale = h3 > 0.0 ? params.fscale * std::cbrt(l3 / h3) : 0.0;

  // Step 5: repulsive forces only.
  for_chunks(pool, bar_count, kChunk, [&](size_t, size_t begin, size_t end) {
    for (size_t b = begin; b < end; ++b) {
      bars.desired[b] *= scale;
      const double length = bars.length[b];
      const double f = std::max(bars.desired[b] - length, 0.0);
      const Vec3 bar = p[topology.bars[b][0]] - p[topology.bars[b][1]];
      push[b] = length > 0.0 ? (f / length) * bar : Vec3{};
    }
  });

  // Steps 7-8 per node: the sum of its bars' pushes, the move, the projection, the measures.
  const size_t n = p.size();
  std::vector<Vec3> next(n);
  struct Partial {
    double max_move = 0.0, max_drift = 0.0, sum_sq = 0.0;
    int64_t interior = 0;
  };
  std::vector<Partial> partial(ThreadPool::chunk_count(n, kChunk));
  const double inside = -params.geps * h0;
  for_chunks(pool, n, kChunk, [&](size_t c, size_t begin, size_t end) {
    Partial& part = partial[c];
    for (size_t i = begin; i < end; ++i) {
      Vec3 force{};
      double own = 0.0;
      const int64_t first = topology.bar_offsets[i], last = topology.bar_offsets[i + 1];
      for (int64_t k = first; k < last; ++k) {
        const int64_t e = topology.bar_ends[k];
        const Vec3 f = push[e >> 1];
        force = (e & 1) ? force - f : force + f;
        own += bars.desired[e >> 1];
      }
      own = last > first ? own / static_cast<double>(last - first) : h0;
      if (static_cast<int64_t>(i) < nodes.fixed) {
        next[i] = p[i];
        continue;
      }
      const Vec3 move = params.deltat * force + params.momentum * nodes.momentum[i];
      nodes.momentum[i] = move;
      Vec3 q = p[i] + move;
      const double d = domain.distance(q);
      if (d > 0.0) q = project_step3d(domain, q, d, params.deps * h0);
      next[i] = q;
      if (d < inside) {
        const double m = norm(move) / own;
        part.max_move = std::max(part.max_move, m);
        part.sum_sq += m * m;
        ++part.interior;
      }
      part.max_drift = std::max(part.max_drift, norm(q - nodes.at_triangulation[i]) / own);
    }
  });
  nodes.points.swap(next);

  StepResult result;
  double sum_sq = 0.0;
  int64_t interior = 0;
  for (const Partial& part : partial) {
    result.max_move = std::max(result.max_move, part.max_move);
    result.max_drift = std::max(result.max_drift, part.max_drift);
    sum_sq += part.sum_sq;
    interior += part.interior;
  }
  result.rms_move = interior > 0 ? std::sqrt(sum_sq / static_cast<double>(interior)) : 0.0;
  return result;
}

std::vector<int32_t> crowded_nodes3d(const Topology3& topology, const BarLengths& bars,
                                     int64_t fixed) {
  std::vector<int32_t> out;
  for (size_t b = 0; b < topology.bars.size(); ++b) {
    if (!(bars.desired[b] > 2.0 * bars.length[b])) continue;
    for (int32_t end : topology.bars[b])
      if (end >= fixed) out.push_back(end);
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

void measure_spacing3d(const Topology3& topology, Nodes3& nodes) {
  const auto& p = nodes.points;
  nodes.spacing.assign(p.size(), 0.0);
  for (size_t i = 0; i < p.size(); ++i) {
    const int64_t first = topology.bar_offsets[i], last = topology.bar_offsets[i + 1];
    if (first == last) continue;
    double sum = 0.0;
    for (int64_t k = first; k < last; ++k) {
      const auto& bar = topology.bars[topology.bar_ends[k] >> 1];
      sum += norm(p[bar[0]] - p[bar[1]]);
    }
    nodes.spacing[i] = sum / static_cast<double>(last - first);
  }
}

std::vector<int32_t> drifted_nodes3d(const Nodes3& nodes, double fraction) {
  const auto& p = nodes.points;
  std::vector<int32_t> out;
  for (size_t i = static_cast<size_t>(nodes.fixed); i < p.size(); ++i)
    if (nodes.spacing[i] > 0.0 &&
        norm(p[i] - nodes.at_triangulation[i]) > fraction * nodes.spacing[i])
      out.push_back(static_cast<int32_t>(i));
  return out;
}

void remove_nodes3d(Nodes3& nodes, const std::vector<int32_t>& indices) {
  std::vector<char> gone(nodes.points.size(), 0);
  for (int32_t i : indices) gone[i] = 1;
  size_t kept = 0;
  for (size_t i = 0; i < nodes.points.size(); ++i) {
    if (gone[i]) continue;
    nodes.points[kept] = nodes.points[i];
    nodes.momentum[kept] = nodes.momentum[i];
    nodes.at_triangulation[kept] = nodes.at_triangulation[i];
    if (!nodes.spacing.empty()) nodes.spacing[kept] = nodes.spacing[i];
    ++kept;
  }
  nodes.points.resize(kept);
  nodes.momentum.resize(kept);
  nodes.at_triangulation.resize(kept);
  if (!nodes.spacing.empty()) nodes.spacing.resize(kept);
}

}  // namespace meshd
