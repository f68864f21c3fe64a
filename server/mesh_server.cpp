#include "server/mesh_server.h"

#include <grpcpp/ext/proto_server_reflection_plugin.h>
#include <grpcpp/health_check_service_interface.h>
#include <spdlog/spdlog.h>

#include "core/common/error.h"
#include "core/common/text_file.h"

namespace meshd {

MeshServer::MeshServer(ServerOptions options, std::vector<WorkerSpec> workers)
    : options_(std::move(options)) {
  if (workers.empty()) workers = workers_for(options_);
  jobs_ = std::make_unique<JobManager>(options_.jobs, std::move(workers), metrics_);
  const std::string token =
      options_.token_file.empty() ? "" : read_first_line(options_.token_file, "--token-file");
  service_ = std::make_unique<MeshService>(*jobs_, metrics_, BearerToken(token));
}

MeshServer::~MeshServer() { shutdown(std::chrono::milliseconds(0)); }

std::shared_ptr<grpc::ServerCredentials> MeshServer::credentials() const {
  if (options_.tls_cert.empty()) return grpc::InsecureServerCredentials();
  grpc::SslServerCredentialsOptions ssl;
  ssl.pem_key_cert_pairs.push_back({read_text_file(options_.tls_key, "--tls-key"),
                                    read_text_file(options_.tls_cert, "--tls-cert")});
  if (!options_.tls_client_ca.empty()) {
    ssl.pem_root_certs = read_text_file(options_.tls_client_ca, "--tls-client-ca");
    ssl.client_certificate_request = GRPC_SSL_REQUEST_AND_REQUIRE_CLIENT_CERTIFICATE_AND_VERIFY;
  }
  return grpc::SslServerCredentials(ssl);
}

void MeshServer::start() {
  grpc::EnableDefaultHealthCheckService(true);
  grpc::reflection::InitProtoReflectionServerBuilderPlugin();
  grpc::ServerBuilder builder;
  int port = 0;
  builder.AddListeningPort(options_.listen, credentials(), &port);
  builder.RegisterService(service_.get());
  builder.SetMaxReceiveMessageSize(options_.max_request_mb << 20);
  server_ = builder.BuildAndStart();
  if (!server_ || port == 0) {
    throw Error(ErrorCode::kUnavailable, "--listen", "cannot listen on " + options_.listen);
  }
  server_->GetHealthCheckService()->SetServingStatus(false);
  port_ = port;
  spdlog::info("meshd listening on {} (port {}){}{}", options_.listen, port,
               options_.tls_cert.empty() ? "" : ", TLS",
               options_.token_file.empty() ? "" : ", bearer token required");
  if (!options_.metrics.empty()) {
    metrics_port_ = metrics_.serve(options_.metrics);
    spdlog::info("metrics at http://{}/metrics (port {})", options_.metrics, metrics_port_.load());
  }
  const auto t = std::chrono::steady_clock::now();
  jobs_->start();
  for (const std::string& w : jobs_->describe_workers()) spdlog::info("worker {}", w);
  server_->GetHealthCheckService()->SetServingStatus(true);
  spdlog::info("serving: warm-up took {:.3f} s",
               std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count());
}

void MeshServer::shutdown(std::chrono::milliseconds grace) {
  if (stopped_) return;
  stopped_ = true;
  // Refuse jobs before health says NOT_SERVING: a client that saw NOT_SERVING must not get a job
  // in (this order was found racing under ASan).
  jobs_->stop_accepting();
  if (server_) server_->GetHealthCheckService()->SetServingStatus(false);
  spdlog::info("shutting down: {} live jobs, {} ms grace", jobs_->live_jobs(), grace.count());
  jobs_->drain(grace);
  // Streams of finished jobs end by themselves; give them a moment to deliver their ends.
  if (server_) server_->Shutdown(std::chrono::system_clock::now() + std::chrono::seconds(2));
  spdlog::info("meshd stopped");
}

}  // namespace meshd
