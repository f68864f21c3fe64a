#include "tests/server/test_server.h"

#include "core/common/sha256.h"

namespace meshd::testing {

v1::MeshRequest disk_request(double h0, v1::JobOptions::Backend backend) {
  v1::MeshRequest request;
  request.mutable_geometry()->mutable_circle()->set_radius(1.0);
  request.set_h0(h0);
  request.mutable_options()->set_backend(backend);
  return request;
}

v1::MeshRequest endless_request() {
  v1::MeshRequest r = disk_request(0.03);
  r.mutable_params()->set_dptol(1e-9);
  r.mutable_params()->set_max_iterations(1'000'000);
  return r;
}

ServerOptions test_options() {
  ServerOptions o;
  o.listen = "127.0.0.1:0";
  o.backend = Backend::kCpu;
  o.drain_timeout_s = 1;
  o.jobs.retention = std::chrono::seconds(60);
  return o;
}

std::vector<WorkerSpec> cpu_workers(int count, unsigned threads) {
  std::vector<WorkerSpec> out;
  for (int i = 0; i < count; ++i)
    out.push_back({"cpu" + std::to_string(i), Backend::kCpu, cpu_engine_factory(threads)});
  return out;
}

TestServer::TestServer(ServerOptions options, std::vector<WorkerSpec> workers)
    : server_(std::make_unique<MeshServer>(std::move(options), std::move(workers))) {
  server_->start();
}

TestServer::~TestServer() { server_->shutdown(std::chrono::milliseconds(0)); }

std::shared_ptr<grpc::Channel> TestServer::channel() const {
  return grpc::CreateChannel(address(), grpc::InsecureChannelCredentials());
}

std::unique_ptr<v1::MeshService::Stub> TestServer::stub() const {
  return v1::MeshService::NewStub(channel());
}

std::vector<std::string> StreamResult::kinds() const {
  std::vector<std::string> out;
  for (const auto& e : events) {
    const auto* field = e.GetDescriptor()->FindOneofByName("event");
    const auto* set = e.GetReflection()->GetOneofFieldDescriptor(e, field);
    out.push_back(set ? set->name() : "none");
  }
  return out;
}

StreamResult read_stream(grpc::ClientReader<v1::MeshEvent>& reader) {
  StreamResult r;
  v1::MeshEvent event;
  while (reader.Read(&event)) {
    if (r.job_id.empty()) r.job_id = event.job_id();
    if (event.has_result_chunk()) {
      r.payload += event.result_chunk().data();
      event.mutable_result_chunk()->clear_data();
    }
    if (event.has_done()) {
      r.has_done = true;
      r.done = event.done();
    }
    r.events.push_back(event);
  }
  r.status = reader.Finish();
  if (r.status.ok() && r.has_done) {
    r.checksum_ok = sha256_hex(r.payload) == r.done.result_sha256() &&
                    r.payload.size() == r.done.result_bytes();
    r.mesh.ParseFromString(r.payload);
  }
  return r;
}

std::unique_ptr<grpc::ClientContext> context_with_deadline(std::chrono::milliseconds timeout) {
  auto context = std::make_unique<grpc::ClientContext>();
  context->set_deadline(std::chrono::system_clock::now() + timeout);
  return context;
}

StreamResult generate(v1::MeshService::Stub& stub, const v1::MeshRequest& request,
                      std::chrono::milliseconds deadline) {
  auto context = context_with_deadline(deadline);
  auto reader = stub.Generate(context.get(), request);
  return read_stream(*reader);
}

}  // namespace meshd::testing
