// meshd assembled: the job manager and its workers, the gRPC server (MeshService, health,
// reflection, optional TLS and token) and the metrics endpoint. Used by main() and, in process,
// by the tests and the benchmark.
//
// Life: start() listens at once with health NOT_SERVING, warms every worker, then turns health
// SERVING. shutdown() turns it NOT_SERVING, refuses new jobs, lets running ones finish for the
// grace period, cancels the rest, and stops the gRPC server.
#pragma once

#include <grpcpp/grpcpp.h>

#include <atomic>
#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include "server/job_manager.h"
#include "server/mesh_service.h"
#include "server/metrics.h"
#include "server/server_options.h"

namespace meshd {

class MeshServer {
 public:
  // `workers` empty: workers_for(options).
  explicit MeshServer(ServerOptions options, std::vector<WorkerSpec> workers = {});
  ~MeshServer();
  MeshServer(const MeshServer&) = delete;
  MeshServer& operator=(const MeshServer&) = delete;

  // Throws Error when an address cannot be bound, a TLS or token file cannot be read, or a
  // worker cannot warm up.
  void start();
  void shutdown(std::chrono::milliseconds grace);

  // 0 until start() has bound the address (then safe to read from any thread).
  int port() const { return port_.load(); }
  int metrics_port() const { return metrics_port_.load(); }
  JobManager& jobs() { return *jobs_; }
  Metrics& metrics() { return metrics_; }

 private:
  std::shared_ptr<grpc::ServerCredentials> credentials() const;

  const ServerOptions options_;
  Metrics metrics_;
  std::unique_ptr<JobManager> jobs_;
  std::unique_ptr<MeshService> service_;
  std::unique_ptr<grpc::Server> server_;
  std::atomic<int> port_{0};
  std::atomic<int> metrics_port_{0};
  bool stopped_ = false;
};

}  // namespace meshd
