#include "tests/server/test_engines.h"

#include <atomic>
#include <stdexcept>
#include <thread>
#include <utility>

#include "core/common/thread_pool.h"
#include "core/distmesh/cpu_engine.h"
#include "tests/core/distmesh/forwarding_engine.h"

namespace meshd::testing {

namespace {

// A one-thread pool, constructed before the engine that uses it.
struct OneThread {
  ThreadPool pool_{1};
};

// The CPU engine (1 thread) as a worker's engine; subclasses hook the calls they need.
class WorkerTestEngine : private OneThread, public ForwardingEngine, public WorkerEngine {
 public:
  WorkerTestEngine() : ForwardingEngine(pool_) {}
  Engine& engine() override { return *this; }
  std::string device() const override { return "test cpu"; }
  const char* name() const override { return "test"; }
};

class GatedEngine final : public WorkerTestEngine {
 public:
  GatedEngine(std::shared_ptr<Gate> gate, bool gate_warm_up)
      : gate_(std::move(gate)), pass_next_(!gate_warm_up) {}
  int64_t initialize(const CompiledProblem& p) override {
    if (!pass_next_) gate_->wait();
    pass_next_ = false;
    return WorkerTestEngine::initialize(p);
  }

 private:
  std::shared_ptr<Gate> gate_;
  bool pass_next_;
};

class FailingEngine final : public WorkerTestEngine {
 public:
  FailingEngine(ErrorCode code, int fail_at) : code_(code), fail_at_(fail_at) {}
  int64_t initialize(const CompiledProblem& p) override {
    steps_ = 0;
    ++jobs_;
    return WorkerTestEngine::initialize(p);
  }
  StepResult move_points() override {
    if (jobs_ > 1 && !failed_ && ++steps_ == fail_at_) {
      failed_ = true;
      if (code_ == ErrorCode::kInternal) throw std::runtime_error("simulated device fault");
      throw Error(code_, "", "simulated: out of memory on the device");
    }
    return WorkerTestEngine::move_points();
  }

 private:
  ErrorCode code_;
  int fail_at_;
  int steps_ = 0;
  int jobs_ = 0;         // the first is the warm-up
  bool failed_ = false;  // once per engine
};

class ThreadLoggingEngine final : public WorkerTestEngine {
 public:
  explicit ThreadLoggingEngine(std::shared_ptr<ThreadLog> threads) : threads_(std::move(threads)) {}
  int64_t initialize(const CompiledProblem& p) override {
    {
      std::lock_guard lock(threads_->mutex);
      threads_->ids.push_back(std::this_thread::get_id());
    }
    return WorkerTestEngine::initialize(p);
  }

 private:
  std::shared_ptr<ThreadLog> threads_;
};

}  // namespace

WorkerEngineFactory thread_logging_cpu_factory(std::shared_ptr<ThreadLog> threads) {
  return [threads] { return std::make_unique<ThreadLoggingEngine>(threads); };
}

WorkerEngineFactory gated_cpu_factory(std::shared_ptr<Gate> gate, bool gate_warm_up) {
  return [gate, gate_warm_up] { return std::make_unique<GatedEngine>(gate, gate_warm_up); };
}

WorkerEngineFactory failing_cpu_factory(ErrorCode code, int fail_at,
                                        std::shared_ptr<std::atomic<int>> builds) {
  return [code, fail_at, builds] {
    ++*builds;
    return std::make_unique<FailingEngine>(code, fail_at);
  };
}

}  // namespace meshd::testing
