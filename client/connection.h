// How meshctl reaches meshd: the address, TLS, the bearer token and the deadline that every call
// carries (clients always set deadlines).
#pragma once

#include <grpcpp/grpcpp.h>

#include <chrono>
#include <memory>
#include <string>

namespace meshd::cli {

struct ConnectionOptions {
  std::string server = "127.0.0.1:50051";
  double deadline_s = 600;  // per call; a Generate of a large mesh needs minutes on a CPU
  bool tls = false;
  std::string tls_ca;    // PEM roots; empty: the system's
  std::string tls_cert;  // client certificate (PEM), with tls_key
  std::string tls_key;
  std::string tls_server_name;  // override the name checked against the certificate
  std::string token;            // bearer token; empty: none
};

// The channel settings of our clients: a result's chunks (1 MiB each) flow on a stream window of
// kResultWindowBytes, in place of HTTP/2's 64 KiB that the transport widens as it goes.
constexpr int kResultWindowBytes = 8 << 20;
grpc::ChannelArguments channel_arguments();

class Connection {
 public:
  // Throws Error(kInvalidArgument) naming the flag when a TLS or token file cannot be read.
  explicit Connection(const ConnectionOptions& options);

  std::shared_ptr<grpc::Channel> channel() const { return channel_; }
  // A context with the deadline and the token set.
  std::unique_ptr<grpc::ClientContext> context() const;

 private:
  ConnectionOptions options_;
  std::shared_ptr<grpc::Channel> channel_;
};

}  // namespace meshd::cli
