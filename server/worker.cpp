#include "server/worker.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <utility>
#include <vector>

#include "core/common/error.h"
#include "core/distmesh/distmesh.h"
#include "core/distmesh3d/generate_mesh3d.h"
#include "server/job_observer.h"
#include "server/request_conversion.h"
#include "server/status_mapping.h"

namespace meshd {

namespace {

double seconds_since(Job::Clock::time_point t) {
  return std::chrono::duration<double>(Job::Clock::now() - t).count();
}

v1::JobOptions::Backend to_proto(Backend b) {
  return b == Backend::kGpu ? v1::JobOptions::BACKEND_GPU : v1::JobOptions::BACKEND_CPU;
}

// A unit disk: every step of the loop once, in well under a second.
JobSpec warm_up_job(double h0) {
  v1::MeshRequest request;
  request.mutable_geometry()->mutable_circle()->set_radius(1.0);
  request.set_h0(h0);
  return to_job_spec(request);
}

// About 400 nodes on any engine. A GPU engine also meshes about 20k nodes, so that its arena
// holds a small job's buffers before the first one comes: the first 2k-node job after a
// 400-node warm-up took 1.8 ms longer than the next ones, a third of its time (bench/RESULTS.md).
std::vector<JobSpec> warm_up_jobs(Backend kind) {
  std::vector<JobSpec> jobs{warm_up_job(0.1)};
  if (kind == Backend::kGpu) jobs.push_back(warm_up_job(0.0125));
  return jobs;
}

}  // namespace

Worker::Worker(std::string name, Backend kind, WorkerEngineFactory factory, JobQueue& queue,
               Metrics& metrics, Hooks hooks)
    : name_(std::move(name)),
      kind_(kind),
      factory_(std::move(factory)),
      queue_(queue),
      metrics_(metrics),
      hooks_(std::move(hooks)) {}

Worker::~Worker() { join(); }

void Worker::warm_up() {
  const auto t = Job::Clock::now();
  engine_ = factory_();
  device_ = engine_->device();
  size_t nodes = 0;
  for (const JobSpec& job : warm_up_jobs(kind_)) {
    const auto t_mesh = Job::Clock::now();
    const MeshResult r = generate_mesh(job.plane, engine_->engine(), nullptr, nullptr);
    queue_.observe_run(kind_, job.estimated_nodes, seconds_since(t_mesh));
    nodes = std::max(nodes, r.mesh.points.size());
  }
  spdlog::info("worker {} warm on {}: up to {} nodes in {:.3f} s", name_, device_, nodes,
               seconds_since(t));
}

std::future<void> Worker::start() {
  std::promise<void> warm;
  std::future<void> outcome = warm.get_future();
  thread_ = std::thread([this, warm = std::move(warm)]() mutable {
    try {
      warm_up();
    } catch (...) {
      warm.set_exception(std::current_exception());
      return;
    }
    warm.set_value();
    may_take_jobs_.wait();
    loop();
  });
  return outcome;
}

void Worker::take_jobs() {
  if (!took_jobs_.exchange(true)) may_take_jobs_.count_down();
}

void Worker::join() {
  take_jobs();
  if (thread_.joinable()) thread_.join();
}

void Worker::loop() {
  while (std::shared_ptr<Job> job = queue_.pop(kind_)) {
    metrics_.set_queue_depth(static_cast<int64_t>(queue_.size()));
    const auto t = Job::Clock::now();
    run(*job);
    queue_.done(*job, kind_, seconds_since(t), job->state() == JobState::kSucceeded);
    if (hooks_.finished) hooks_.finished(*job);
    if (!engine_ && !rebuild_engine()) {
      retired_ = true;
      if (hooks_.retired) hooks_.retired(*this);
      return;
    }
  }
}

bool Worker::rebuild_engine() {
  try {
    engine_ = factory_();
    spdlog::warn("worker {}: engine rebuilt on {}", name_, engine_->device());
    return true;
  } catch (const std::exception& e) {
    spdlog::error("worker {}: cannot rebuild its engine, retiring: {}", name_, e.what());
    return false;
  }
}

template <typename Result>
EncodedResult Worker::encode_and_publish(Job& job, const Result& result) {
  std::shared_ptr<const ResultPayload> payload =
      encode_payload(result, engine_->engine().host_pool());
  // The chunks go out while the checksum is taken: 3 ms of a 100k-node result's.
  job.publish_payload(payload);
  return encode_done(result, std::move(payload));
}

EncodedResult Worker::run_plane(Job& job, Observer& observer, Job::Clock::time_point t) {
  const MeshResult result =
      generate_mesh(job.spec().plane, engine_->engine(), &observer, job.cancel_flag());
  const double t_mesh = seconds_since(t);
  EncodedResult encoded = encode_and_publish(job, result);
  spdlog::info(
      "job {} succeeded on {}: {} nodes, {} triangles, {} iterations{}, q_min {:.3f}, mesh "
      "{:.3f} s, encode {:.3f} s, {} bytes",
      job.id(), name_, result.mesh.points.size(), result.mesh.triangles.size(),
      result.stats.iterations, result.stats.converged ? "" : " (max_iterations, not converged)",
      result.quality.q_min, t_mesh, seconds_since(t) - t_mesh, encoded.payload->bytes.size());
  return encoded;
}

EncodedResult Worker::run_volume(Job& job, Observer& observer, Job::Clock::time_point t) {
  const MeshResult3 result = generate_mesh3d(*job.spec().volume, engine_->engine().host_pool(),
                                             &observer, job.cancel_flag(), engine_->engine3());
  const double t_mesh = seconds_since(t);
  EncodedResult encoded = encode_and_publish(job, result);
  spdlog::info(
      "job {} succeeded on {}: {} nodes, {} tetrahedra, {} iterations{}, q_min {:.3f}, min "
      "dihedral {:.1f} deg, mesh {:.3f} s, encode {:.3f} s, {} bytes",
      job.id(), name_, result.mesh.points.size(), result.mesh.tets.size(), result.stats.iterations,
      result.stats.converged ? "" : " (max_iterations, not converged)", result.quality.q_min,
      result.quality.min_dihedral_deg, t_mesh, seconds_since(t) - t_mesh,
      encoded.payload->bytes.size());
  return encoded;
}

void Worker::run(Job& job) {
  if (Job::Clock::now() > job.deadline()) {
    job.finish(grpc::Status(grpc::StatusCode::DEADLINE_EXCEEDED,
                            "the job's deadline passed while it was queued"));
    return;
  }
  v1::Started started;
  started.set_backend(to_proto(kind_));
  started.set_device(device_);
  if (!job.start(started)) {
    job.finish(job.stop_status());
    return;
  }
  const auto t = Job::Clock::now();
  metrics_.observe_queue_wait(kind_, std::chrono::duration<double>(t - job.submitted()).count());
  spdlog::info("job {} started on {} ({}), about {:.0f} nodes", job.id(), name_, device_,
               job.spec().estimated_nodes);
  try {
    JobObserver observer(job);
    job.succeed(job.spec().volume ? run_volume(job, observer, t) : run_plane(job, observer, t));
  } catch (const Error& e) {
    const grpc::Status status =
        e.code() == ErrorCode::kCancelled ? job.stop_status() : to_grpc_status(e);
    spdlog::info("job {} ended on {}: {} {}", job.id(), name_, error_code_name(e.code()),
                 status.error_message());
    job.finish(status);
    // A device that failed may be left in any state: start the next job on a fresh engine.
    if (e.code() == ErrorCode::kInternal) engine_.reset();
  } catch (...) {
    const grpc::Status status = to_grpc_status(std::current_exception());
    spdlog::error("job {} failed on {}: {}", job.id(), name_, status.error_message());
    job.finish(status);
    engine_.reset();
  }
  metrics_.observe_run(kind_, seconds_since(t));
  if (engine_ && engine_->device_index() >= 0) {
    try {
      metrics_.set_device_memory(engine_->device_index(), engine_->device_memory_bytes());
    } catch (const std::exception&) {
      // The metric is best effort; the next job finds out whether the device still works.
    }
  }
}

}  // namespace meshd
