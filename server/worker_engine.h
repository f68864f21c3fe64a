// What a worker runs its jobs on: an engine, and the words that say where it runs. The factory
// builds a fresh one, so that a worker can rebuild an engine that failed; tests inject their own.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "core/distmesh/engine.h"
#include "core/distmesh3d/engine3.h"

namespace meshd {

class WorkerEngine {
 public:
  virtual ~WorkerEngine() = default;
  virtual Engine& engine() = 0;
  // The engine of 3D jobs' steps; null: the CPU's, on engine().host_pool().
  virtual Engine3* engine3() { return nullptr; }
  // "cpu (8 threads)", "NVIDIA H100 80GB HBM3 (device 0)".
  virtual std::string device() const = 0;
  // CUDA device ordinal, -1 for the CPU.
  virtual int device_index() const { return -1; }
  // Device memory in use, for the metrics; 0 for the CPU.
  virtual int64_t device_memory_bytes() const { return 0; }
};

using WorkerEngineFactory = std::function<std::unique_ptr<WorkerEngine>()>;

// The CPU engine on a pool of `threads` threads (0: all cores).
WorkerEngineFactory cpu_engine_factory(unsigned threads);

// CUDA devices this build can use: 0 when built without CUDA or when none is visible. The
// first call sets the process up for many GPU workers (share_gpus_among_engines in
// kernels/gpu_engine.h): call it before anything else touches CUDA.
int usable_gpu_count();
// Whether that setup holds on `device`: every kernel loaded at the context's start, and threads
// that yield while they wait. False in a build without the GPU engine.
bool gpus_shared_among_workers(int device);

// Device allocations made so far in this process by the GPU engines (0 in a build without them),
// so that a test can hold a warm worker's first small job to none.
int64_t gpu_allocation_count();

// The GPU engine on `device`, with a pool of `host_threads` threads for the host's share of its
// jobs; its context is created when built (the worker's warm-up meshes on it, worker.h). Throws
// Error(kUnavailable) when this build has no GPU engine.
WorkerEngineFactory gpu_engine_factory(int device, unsigned host_threads);

}  // namespace meshd
