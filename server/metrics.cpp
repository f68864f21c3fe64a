#include "server/metrics.h"

#include <prometheus/counter.h>
#include <prometheus/exposer.h>
#include <prometheus/gauge.h>
#include <prometheus/histogram.h>
#include <prometheus/registry.h>
#include <prometheus/text_serializer.h>

#include <sstream>

#include "core/common/error.h"

namespace meshd {

namespace {

// Seconds, from a 1k-node job on a GPU to a 5M-node job on the CPU.
const prometheus::Histogram::BucketBoundaries& time_buckets() {
  static const prometheus::Histogram::BucketBoundaries kBuckets{
      0.001, 0.003, 0.01, 0.03, 0.1, 0.3, 1, 3, 10, 30, 100, 300, 1000};
  return kBuckets;
}

}  // namespace

Metrics::Metrics() : registry_(std::make_shared<prometheus::Registry>()) {
  jobs_ = &prometheus::BuildCounter()
               .Name("meshd_jobs_total")
               .Help("Jobs by outcome: succeeded, failed, cancelled, or rejected before queueing")
               .Register(*registry_);
  for (const char* outcome : {"succeeded", "failed", "cancelled", "rejected"})
    jobs_->Add({{"outcome", outcome}});
  device_memory_ = &prometheus::BuildGauge()
                        .Name("meshd_device_memory_bytes")
                        .Help("Device memory held by the GPU engines' arenas")
                        .Register(*registry_);
  queue_wait_ = &prometheus::BuildHistogram()
                     .Name("meshd_queue_wait_seconds")
                     .Help("Time from submission to start, by backend")
                     .Register(*registry_);
  run_ = &prometheus::BuildHistogram()
              .Name("meshd_run_seconds")
              .Help("Time from start to the end of the job, by backend")
              .Register(*registry_);
  queue_depth_ = &prometheus::BuildGauge()
                      .Name("meshd_queue_depth")
                      .Help("Jobs waiting for a worker")
                      .Register(*registry_)
                      .Add({});
  live_jobs_ = &prometheus::BuildGauge()
                    .Name("meshd_live_jobs")
                    .Help("Jobs queued or running")
                    .Register(*registry_)
                    .Add({});
  streams_ = &prometheus::BuildGauge()
                  .Name("meshd_active_streams")
                  .Help("Open Generate and Watch streams")
                  .Register(*registry_)
                  .Add({});
}

Metrics::~Metrics() = default;

int Metrics::serve(const std::string& address) {
  try {
    exposer_ = std::make_unique<prometheus::Exposer>(address);
  } catch (const std::exception& e) {
    throw Error(ErrorCode::kUnavailable, "metrics",
                "cannot serve metrics on " + address + ": " + e.what());
  }
  exposer_->RegisterCollectable(registry_);
  const auto ports = exposer_->GetListeningPorts();
  return ports.empty() ? 0 : ports.front();
}

void Metrics::count_job(const char* outcome) { jobs_->Add({{"outcome", outcome}}).Increment(); }
void Metrics::set_queue_depth(int64_t depth) { queue_depth_->Set(static_cast<double>(depth)); }
void Metrics::add_live_jobs(int64_t delta) { live_jobs_->Increment(static_cast<double>(delta)); }
void Metrics::add_streams(int64_t delta) { streams_->Increment(static_cast<double>(delta)); }

void Metrics::observe_queue_wait(Backend backend, double seconds) {
  queue_wait_->Add({{"backend", backend_name(backend)}}, time_buckets()).Observe(seconds);
}

void Metrics::observe_run(Backend backend, double seconds) {
  run_->Add({{"backend", backend_name(backend)}}, time_buckets()).Observe(seconds);
}

void Metrics::set_device_memory(int device, int64_t bytes) {
  device_memory_->Add({{"device", std::to_string(device)}}).Set(static_cast<double>(bytes));
}

std::string Metrics::text() const {
  std::ostringstream out;
  prometheus::TextSerializer().Serialize(out, registry_->Collect());
  return out.str();
}

}  // namespace meshd
