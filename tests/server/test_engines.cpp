#include "tests/server/test_engines.h"

#include <atomic>
#include <stdexcept>

#include "core/common/thread_pool.h"
#include "core/distmesh/cpu_engine.h"

namespace meshd::testing {

namespace {

// Forwards everything to a CpuEngine; subclasses hook the calls they need.
class ForwardingEngine : public Engine, public WorkerEngine {
 public:
  ForwardingEngine() : pool_(1), cpu_(pool_) {}
  Engine& engine() override { return *this; }
  std::string device() const override { return "test cpu"; }

  const char* name() const override { return "test"; }
  int64_t initialize(const CompiledProblem& p) override { return cpu_.initialize(p); }
  int64_t load_points(const CompiledProblem& p, const std::vector<Vec2>& pts) override {
    return cpu_.load_points(p, pts);
  }
  TopologyStats retriangulate(bool full) override { return cpu_.retriangulate(full); }
  int64_t remove_crowded_points() override { return cpu_.remove_crowded_points(); }
  StepResult move_points() override { return cpu_.move_points(); }
  void remove_points(const std::vector<int32_t>& i) override { cpu_.remove_points(i); }
  int64_t node_count() const override { return cpu_.node_count(); }
  void read_points(std::vector<Vec2>& p) override { cpu_.read_points(p); }
  void read_triangles(std::vector<std::array<int32_t, 3>>& t) override { cpu_.read_triangles(t); }

 protected:
  ThreadPool pool_;
  CpuEngine cpu_;
};

class GatedEngine final : public ForwardingEngine {
 public:
  GatedEngine(std::shared_ptr<Gate> gate, bool gate_warm_up)
      : gate_(std::move(gate)), pass_next_(!gate_warm_up) {}
  int64_t initialize(const CompiledProblem& p) override {
    if (!pass_next_) gate_->wait();
    pass_next_ = false;
    return ForwardingEngine::initialize(p);
  }

 private:
  std::shared_ptr<Gate> gate_;
  bool pass_next_;
};

class FailingEngine final : public ForwardingEngine {
 public:
  FailingEngine(ErrorCode code, int fail_at) : code_(code), fail_at_(fail_at) {}
  int64_t initialize(const CompiledProblem& p) override {
    steps_ = 0;
    ++jobs_;
    return ForwardingEngine::initialize(p);
  }
  StepResult move_points() override {
    if (jobs_ > 1 && !failed_ && ++steps_ == fail_at_) {
      failed_ = true;
      if (code_ == ErrorCode::kInternal) throw std::runtime_error("simulated device fault");
      throw Error(code_, "", "simulated: out of memory on the device");
    }
    return ForwardingEngine::move_points();
  }

 private:
  ErrorCode code_;
  int fail_at_;
  int steps_ = 0;
  int jobs_ = 0;         // the first is the warm-up
  bool failed_ = false;  // once per engine
};

}  // namespace

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
