// Engines for the service tests: one that waits at a gate before each job (to hold a worker
// busy or a warm-up pending for as long as a test needs), and one that fails mid-job the way a
// device can (out of memory, or a fault).
#pragma once

#include <condition_variable>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "core/common/error.h"
#include "server/worker_engine.h"

namespace meshd::testing {

class Gate {
 public:
  void open() {
    std::lock_guard lock(mutex_);
    open_ = true;
    changed_.notify_all();
  }
  void wait() {
    std::unique_lock lock(mutex_);
    ++waiting_;
    changed_.notify_all();
    changed_.wait(lock, [&] { return open_; });
    --waiting_;
  }
  // Blocks until someone waits at the gate.
  void wait_for_waiter() {
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [&] { return waiting_ > 0 || open_; });
  }

 private:
  std::mutex mutex_;
  std::condition_variable changed_;
  bool open_ = false;
  int waiting_ = 0;
};

// The CPU engine (1 thread), behind `gate` at each initialize(). With `gate_warm_up` false the
// first initialize (the worker's warm-up) passes freely.
WorkerEngineFactory gated_cpu_factory(std::shared_ptr<Gate> gate, bool gate_warm_up);

// The CPU engine (1 thread) whose move_points fails once, at the `fail_at`-th step of its first
// job after the warm-up: Error(code), or a std::runtime_error for kInternal (a device fault).
// `builds` counts the engines the factory made.
WorkerEngineFactory failing_cpu_factory(ErrorCode code, int fail_at,
                                        std::shared_ptr<std::atomic<int>> builds);

// The threads an engine's calls ran on, in order.
struct ThreadLog {
  std::mutex mutex;
  std::vector<std::thread::id> ids;
};

// The CPU engine (1 thread) that adds the id of the thread of each initialize() (the warm-ups'
// and each job's) to `threads`.
WorkerEngineFactory thread_logging_cpu_factory(std::shared_ptr<ThreadLog> threads);

}  // namespace meshd::testing
