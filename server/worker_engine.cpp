#include "server/worker_engine.h"

#include <mutex>
#include <string>

#include "core/common/error.h"
#include "core/common/thread_pool.h"
#include "core/distmesh/cpu_engine.h"
#ifdef MESHD_HAVE_CUDA
#include "kernels/gpu_engine.h"
#include "kernels/gpu_engine3.h"
#endif

namespace meshd {

namespace {

class CpuWorkerEngine final : public WorkerEngine {
 public:
  explicit CpuWorkerEngine(unsigned threads) : pool_(threads), engine_(pool_) {}
  Engine& engine() override { return engine_; }
  std::string device() const override {
    return "cpu (" + std::to_string(pool_.size()) + " threads)";
  }

 private:
  ThreadPool pool_;
  CpuEngine engine_;
};

#ifdef MESHD_HAVE_CUDA
class GpuWorkerEngine final : public WorkerEngine {
 public:
  GpuWorkerEngine(int device, unsigned host_threads)
      : host_pool_(host_threads),
        engine_(device),
        engine3_(device),
        name_(gpu_device_name(device) + " (device " + std::to_string(device) + ")") {
    engine_.set_host_pool(&host_pool_);
  }
  Engine& engine() override { return engine_; }
  Engine3* engine3() override { return &engine3_; }
  std::string device() const override { return name_; }
  int device_index() const override { return engine_.device(); }
  int64_t device_memory_bytes() const override { return gpu_memory_in_use(engine_.device()); }

 private:
  ThreadPool host_pool_;
  GpuEngine engine_;
  GpuEngine3 engine3_;
  std::string name_;
};
#endif

}  // namespace

WorkerEngineFactory cpu_engine_factory(unsigned threads) {
  return [threads] { return std::make_unique<CpuWorkerEngine>(threads); };
}

int usable_gpu_count() {
#ifdef MESHD_HAVE_CUDA
  // The first call of a server's process: its workers share the devices (gpu_engine.h).
  static std::once_flag shared;
  std::call_once(shared, share_gpus_among_engines);
  return gpu_device_count();
#else
  return 0;
#endif
}

bool gpus_shared_among_workers(int device) {
#ifdef MESHD_HAVE_CUDA
  return gpu_kernels_load_eagerly() && gpu_waits_yield(device);
#else
  (void)device;
  return false;
#endif
}

int64_t gpu_allocation_count() {
#ifdef MESHD_HAVE_CUDA
  return GpuEngine::device_allocations();
#else
  return 0;
#endif
}

WorkerEngineFactory gpu_engine_factory(int device, unsigned host_threads) {
#ifdef MESHD_HAVE_CUDA
  return [device, host_threads] { return std::make_unique<GpuWorkerEngine>(device, host_threads); };
#else
  (void)device;
  (void)host_threads;
  throw Error(ErrorCode::kUnavailable, "backend", "this build of meshd has no GPU engine");
#endif
}

}  // namespace meshd
