#include "client/connection.h"

#include "core/common/text_file.h"

namespace meshd::cli {

grpc::ChannelArguments channel_arguments() {
  grpc::ChannelArguments arguments;
  arguments.SetInt(GRPC_ARG_HTTP2_STREAM_LOOKAHEAD_BYTES, kResultWindowBytes);
  return arguments;
}

Connection::Connection(const ConnectionOptions& options) : options_(options) {
  std::shared_ptr<grpc::ChannelCredentials> credentials;
  grpc::ChannelArguments arguments = channel_arguments();
  if (options.tls || !options.tls_ca.empty() || !options.tls_cert.empty()) {
    grpc::SslCredentialsOptions ssl;
    if (!options.tls_ca.empty()) ssl.pem_root_certs = read_text_file(options.tls_ca, "--tls-ca");
    if (!options.tls_cert.empty()) {
      ssl.pem_cert_chain = read_text_file(options.tls_cert, "--tls-cert");
      ssl.pem_private_key = read_text_file(options.tls_key, "--tls-key");
    }
    credentials = grpc::SslCredentials(ssl);
    if (!options.tls_server_name.empty())
      arguments.SetSslTargetNameOverride(options.tls_server_name);
  } else {
    credentials = grpc::InsecureChannelCredentials();
  }
  channel_ = grpc::CreateCustomChannel(options.server, credentials, arguments);
}

std::unique_ptr<grpc::ClientContext> Connection::context() const {
  auto context = std::make_unique<grpc::ClientContext>();
  context->set_deadline(std::chrono::system_clock::now() +
                        std::chrono::duration_cast<std::chrono::system_clock::duration>(
                            std::chrono::duration<double>(options_.deadline_s)));
  if (!options_.token.empty()) context->AddMetadata("authorization", "Bearer " + options_.token);
  return context;
}

}  // namespace meshd::cli
