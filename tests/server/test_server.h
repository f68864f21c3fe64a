// An in-process meshd on 127.0.0.1 (a free port) for the service tests, and client helpers:
// requests, a channel with the client's default limits, and a stream reader that collects every
// event and checks the result against its checksum.
#pragma once

#include <grpcpp/grpcpp.h>

#include <chrono>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "meshd/v1/mesh.pb.h"
#include "meshd/v1/service.grpc.pb.h"
#include "server/mesh_server.h"

namespace meshd::testing {

// A unit disk at edge length h0 (about 3.6 / h0^2 nodes), on the given backend.
v1::MeshRequest disk_request(double h0,
                             v1::JobOptions::Backend backend = v1::JobOptions::BACKEND_AUTO);

// A disk that never settles (dptol far below what the nodes reach): it runs until stopped.
v1::MeshRequest endless_request();

// Polls `done` until it holds (true) or `timeout` passes (false).
template <typename Predicate>
bool eventually(Predicate done, std::chrono::milliseconds timeout = std::chrono::seconds(10)) {
  const auto until = std::chrono::steady_clock::now() + timeout;
  while (!done()) {
    if (std::chrono::steady_clock::now() > until) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return true;
}

// Server options for tests: port 0, metrics off, short retention and drain.
ServerOptions test_options();

// CPU workers for tests: `count` workers of `threads` threads each.
std::vector<WorkerSpec> cpu_workers(int count, unsigned threads = 1);

class TestServer {
 public:
  explicit TestServer(ServerOptions options = test_options(),
                      std::vector<WorkerSpec> workers = cpu_workers(1));
  ~TestServer();

  MeshServer& server() { return *server_; }
  std::string address() const { return "127.0.0.1:" + std::to_string(server_->port()); }
  std::shared_ptr<grpc::Channel> channel() const;
  std::unique_ptr<v1::MeshService::Stub> stub() const;

 private:
  std::unique_ptr<MeshServer> server_;
};

// Everything one Generate or Watch stream delivered.
struct StreamResult {
  grpc::Status status;
  std::vector<v1::MeshEvent> events;  // result chunks' data cleared after assembly
  std::string payload;                // concatenated result chunks
  bool has_done = false;
  v1::Done done;
  v1::MeshData mesh;         // parsed payload, when the stream ended OK
  bool checksum_ok = false;  // SHA-256 of payload equals done.result_sha256
  std::string job_id;
  // The events' kinds in order, e.g. "queued started progress ... result_chunk done".
  std::vector<std::string> kinds() const;
};

// Reads `reader` to its end.
StreamResult read_stream(grpc::ClientReader<v1::MeshEvent>& reader);

// Generate with a deadline of `deadline` from now.
StreamResult generate(v1::MeshService::Stub& stub, const v1::MeshRequest& request,
                      std::chrono::milliseconds deadline = std::chrono::seconds(60));

// A context with a deadline `timeout` from now (clients always set deadlines).
std::unique_ptr<grpc::ClientContext> context_with_deadline(
    std::chrono::milliseconds timeout = std::chrono::seconds(30));

}  // namespace meshd::testing
