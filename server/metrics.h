// The service's Prometheus metrics: queue depth, queue wait and run time by backend, jobs by
// outcome, live jobs and streams, device memory in use. Served over HTTP by serve(); text()
// gives the same exposition for tests. Thread-safe (prometheus-cpp's metrics are atomic).
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "server/job_spec.h"

namespace prometheus {
class Counter;
class Exposer;
class Gauge;
class Histogram;
class Registry;
template <typename T>
class Family;
}  // namespace prometheus

namespace meshd {

class Metrics {
 public:
  Metrics();
  ~Metrics();
  Metrics(const Metrics&) = delete;
  Metrics& operator=(const Metrics&) = delete;

  // Serves /metrics on `address` ("127.0.0.1:9090"; port 0 picks a free one). Returns the port.
  // Throws Error(kUnavailable) when the address cannot be bound.
  int serve(const std::string& address);

  // Outcomes: "succeeded", "failed", "cancelled", and "rejected" for requests that never queued.
  void count_job(const char* outcome);
  void set_queue_depth(int64_t depth);
  void add_live_jobs(int64_t delta);
  void add_streams(int64_t delta);
  void observe_queue_wait(Backend backend, double seconds);
  void observe_run(Backend backend, double seconds);
  void set_device_memory(int device, int64_t bytes);

  // The text exposition format, as /metrics serves it.
  std::string text() const;

 private:
  std::shared_ptr<prometheus::Registry> registry_;
  prometheus::Family<prometheus::Counter>* jobs_;
  prometheus::Family<prometheus::Gauge>* device_memory_;
  prometheus::Family<prometheus::Histogram>* queue_wait_;
  prometheus::Family<prometheus::Histogram>* run_;
  prometheus::Gauge* queue_depth_;
  prometheus::Gauge* live_jobs_;
  prometheus::Gauge* streams_;
  std::unique_ptr<prometheus::Exposer> exposer_;
};

}  // namespace meshd
