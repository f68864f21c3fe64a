#include "server/run_time_model.h"

#include <algorithm>
#include <cmath>

namespace meshd {

namespace {

// Priors, from bench/RESULTS.md: a warm GPU worker spends about 10 ms on a small job and
// 0.6 us per node on a large one; one CPU core about 2 ms and 30 us per node.
constexpr double kGpuSecondsPerJob = 10e-3;
constexpr double kGpuSecondsPerNode = 0.6e-6;
constexpr double kCpuSecondsPerJob = 2e-3;
constexpr double kCpuSecondsPerNode = 30e-6;
// Weight of the newest measurement in its class's moving average.
constexpr double kNewestWeight = 0.2;

double prior(Backend kind, double nodes) {
  return kind == Backend::kGpu ? kGpuSecondsPerJob + kGpuSecondsPerNode * nodes
                               : kCpuSecondsPerJob + kCpuSecondsPerNode * nodes;
}

int size_class(double nodes, int classes) {
  return std::clamp(static_cast<int>(std::log2(std::max(nodes, 1.0))), 0, classes - 1);
}

}  // namespace

double RunTimeModel::predict(Backend kind, double nodes) const {
  const Classes& c = classes(kind);
  const int home = size_class(nodes, kSizeClasses);
  // The nearest class with a measurement, the smaller one first on a tie.
  for (int distance = 0; distance < kSizeClasses; ++distance) {
    for (const int k : {home - distance, home + distance}) {
      if (k >= 0 && k < kSizeClasses && c[k].samples > 0)
        return prior(kind, nodes) * std::exp(c[k].log_ratio);
    }
  }
  return prior(kind, nodes);
}

void RunTimeModel::observe(Backend kind, double nodes, double seconds) {
  if (!(seconds > 0) || !(nodes > 0)) return;
  SizeClass& c = classes(kind)[size_class(nodes, kSizeClasses)];
  const double log_ratio = std::log(seconds / prior(kind, nodes));
  c.log_ratio =
      c.samples == 0 ? log_ratio : c.log_ratio + kNewestWeight * (log_ratio - c.log_ratio);
  ++c.samples;
}

}  // namespace meshd
