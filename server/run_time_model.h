// How long a job is expected to run on each kind of worker, from its estimated node count, so
// that the queue can send a job where it will finish first.
//
// A prior (a fixed cost per job plus a cost per node: rough figures for a warm H100 and for one
// CPU core) is corrected by what this server's workers measure, per size class (a power of two
// of nodes): each class keeps a moving average of log(measured / prior), and a size with no
// measurement yet borrows the nearest class that has one. Not thread-safe: the queue holds it
// under its own mutex.
#pragma once

#include <array>

#include "server/job_spec.h"

namespace meshd {

class RunTimeModel {
 public:
  // Expected seconds of a job of about `nodes` nodes on a worker of `kind` (kGpu or kCpu).
  double predict(Backend kind, double nodes) const;
  // A job of about `nodes` nodes (the estimate it was queued with) took `seconds` on `kind`.
  void observe(Backend kind, double nodes, double seconds);

 private:
  static constexpr int kSizeClasses = 32;  // 1 to 2^32 nodes
  struct SizeClass {
    double log_ratio = 0;  // moving average of log(measured / prior)
    int samples = 0;
  };
  using Classes = std::array<SizeClass, kSizeClasses>;

  const Classes& classes(Backend kind) const { return kind == Backend::kGpu ? gpu_ : cpu_; }
  Classes& classes(Backend kind) { return kind == Backend::kGpu ? gpu_ : cpu_; }

  Classes gpu_{}, cpu_{};
};

}  // namespace meshd
