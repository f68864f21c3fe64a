// TLS, client certificates and the bearer token, end to end through real gRPC channels: for each
// server setting, what it lets in and what it keeps out. The certificates are made per test
// process by make_test_certs.sh (the openssl CLI), so no key material lives in the repository.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "grpc/health/v1/health.grpc.pb.h"
#include "tests/server/test_server.h"

namespace meshd::testing {
namespace {

namespace fs = std::filesystem;

// Calls that must be refused fail within this; a hang shows up as DEADLINE_EXCEEDED.
constexpr auto kRefusalDeadline = std::chrono::seconds(20);

// The files of make_test_certs.sh, made once per process into a fresh directory.
class Certs {
 public:
  static const Certs& get() {
    static const Certs certs;
    return certs;
  }
  ~Certs() {
    std::error_code ignored;
    if (!dir_.empty()) fs::remove_all(dir_, ignored);
  }

  bool ok() const { return ok_; }
  const std::string& log() const { return log_; }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::string pem(const std::string& name) const {
    std::ifstream in(path(name));
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
  }

 private:
  Certs() {
    std::string templ = (fs::temp_directory_path() / "meshd_tls_test_XXXXXX").string();
    if (mkdtemp(templ.data()) == nullptr) {
      log_ = "mkdtemp failed";
      return;
    }
    dir_ = templ;
    const std::string command =
        "sh '" MESHD_MAKE_TEST_CERTS "' '" + dir_.string() + "' > '" + path("make.log") + "' 2>&1";
    ok_ = std::system(command.c_str()) == 0;
    log_ = command + ":\n" + pem("make.log");
  }

  fs::path dir_;
  bool ok_ = false;
  std::string log_;
};

// A TLS channel that trusts `ca`, presenting `client` (a make_test_certs.sh name) when given.
std::shared_ptr<grpc::Channel> tls_channel(const std::string& address, const std::string& ca,
                                           const std::string& client = "") {
  const Certs& certs = Certs::get();
  grpc::SslCredentialsOptions ssl;
  ssl.pem_root_certs = certs.pem(ca + ".pem");
  if (!client.empty()) {
    ssl.pem_private_key = certs.pem(client + ".key");
    ssl.pem_cert_chain = certs.pem(client + ".pem");
  }
  return grpc::CreateChannel(address, grpc::SslCredentials(ssl));
}

std::shared_ptr<grpc::Channel> plaintext_channel(const std::string& address) {
  return grpc::CreateChannel(address, grpc::InsecureChannelCredentials());
}

StreamResult generate_on(const std::shared_ptr<grpc::Channel>& channel,
                         std::chrono::milliseconds deadline = std::chrono::seconds(60)) {
  return generate(*v1::MeshService::NewStub(channel), disk_request(0.2), deadline);
}

void expect_meshed(const StreamResult& r) {
  EXPECT_TRUE(r.status.ok()) << r.status.error_code() << ": " << r.status.error_message();
  EXPECT_TRUE(r.has_done);
  EXPECT_TRUE(r.checksum_ok);
  EXPECT_GT(r.mesh.triangles_size(), 0);
}

// Refused before any job exists: no events, and the given code.
void expect_refused(const StreamResult& r, grpc::StatusCode code) {
  EXPECT_EQ(r.status.error_code(), code) << r.status.error_message();
  EXPECT_TRUE(r.events.empty()) << "a refused client got " << r.events.size() << " events";
}

class TlsTest : public ::testing::Test {
 protected:
  void SetUp() override { ASSERT_TRUE(Certs::get().ok()) << Certs::get().log(); }

  // Options for a TLS server; with `require_client_certificate`, clients must present a
  // certificate signed by the test CA.
  static ServerOptions tls_options(bool require_client_certificate) {
    const Certs& certs = Certs::get();
    ServerOptions o = test_options();
    o.tls_cert = certs.path("server.pem");
    o.tls_key = certs.path("server.key");
    if (require_client_certificate) o.tls_client_ca = certs.path("ca.pem");
    return o;
  }
};

TEST_F(TlsTest, ClientTrustingTheCaMeshes) {
  TestServer server(tls_options(false));
  expect_meshed(generate_on(tls_channel(server.address(), "ca")));
}

TEST_F(TlsTest, PlaintextClientIsRefused) {
  TestServer server(tls_options(false));
  expect_refused(generate_on(plaintext_channel(server.address()), kRefusalDeadline),
                 grpc::StatusCode::UNAVAILABLE);
}

// The server presents the configured chain: a client trusting only another CA hangs up.
TEST_F(TlsTest, ClientTrustingAnotherCaIsRefused) {
  TestServer server(tls_options(false));
  expect_refused(generate_on(tls_channel(server.address(), "rogue_ca"), kRefusalDeadline),
                 grpc::StatusCode::UNAVAILABLE);
}

TEST_F(TlsTest, ClientCertificateSignedByTheCaMeshes) {
  TestServer server(tls_options(true));
  expect_meshed(generate_on(tls_channel(server.address(), "ca", "client")));
}

TEST_F(TlsTest, ClientWithoutCertificateIsRefused) {
  TestServer server(tls_options(true));
  expect_refused(generate_on(tls_channel(server.address(), "ca"), kRefusalDeadline),
                 grpc::StatusCode::UNAVAILABLE);
  EXPECT_TRUE(server.server().jobs().list(v1::JOB_STATE_UNSPECIFIED).empty());
}

TEST_F(TlsTest, ClientCertificateFromAnotherCaIsRefused) {
  TestServer server(tls_options(true));
  expect_refused(generate_on(tls_channel(server.address(), "ca", "rogue"), kRefusalDeadline),
                 grpc::StatusCode::UNAVAILABLE);
  EXPECT_TRUE(server.server().jobs().list(v1::JOB_STATE_UNSPECIFIED).empty());
}

// ---- Bearer token -------------------------------------------------------------------------------

class BearerTokenTest : public ::testing::Test {
 protected:
  static constexpr const char* kToken = "meshd-test-token-4f1c";

  void SetUp() override {
    ASSERT_TRUE(Certs::get().ok()) << Certs::get().log();
    token_file_ = Certs::get().path("token");  // in this process's own directory
    // Surrounding white space and a second line are not part of the token.
    std::ofstream(token_file_) << "  " << kToken << " \nnot the token\n";
    ServerOptions o = test_options();
    o.token_file = token_file_;
    server_ = std::make_unique<TestServer>(o);
  }

  // Generate with the metadata "authorization: <authorization>" (none when empty).
  StreamResult generate_with(const std::string& authorization) {
    auto context = context_with_deadline(kRefusalDeadline);
    if (!authorization.empty()) context->AddMetadata("authorization", authorization);
    auto reader = server_->stub()->Generate(context.get(), disk_request(0.2));
    return read_stream(*reader);
  }

  grpc::Status list_jobs_with(const std::string& authorization) {
    auto context = context_with_deadline(kRefusalDeadline);
    if (!authorization.empty()) context->AddMetadata("authorization", authorization);
    v1::ListJobsResponse reply;
    return server_->stub()->ListJobs(context.get(), v1::ListJobsRequest(), &reply);
  }

  bool no_jobs() { return server_->server().jobs().list(v1::JOB_STATE_UNSPECIFIED).empty(); }

  std::string token_file_;
  std::unique_ptr<TestServer> server_;
};

TEST_F(BearerTokenTest, NoTokenIsUnauthenticated) {
  expect_refused(generate(*server_->stub(), disk_request(0.2), kRefusalDeadline),
                 grpc::StatusCode::UNAUTHENTICATED);
  EXPECT_EQ(list_jobs_with("").error_code(), grpc::StatusCode::UNAUTHENTICATED);
  EXPECT_TRUE(no_jobs()) << "an unauthenticated request reached the queue";
}

TEST_F(BearerTokenTest, WrongTokenIsUnauthenticated) {
  const std::string token = kToken;
  const std::vector<std::string> wrong_ones = {
      "Bearer wrong",
      "Bearer " + token.substr(0, token.size() - 1),  // a prefix of the token
      "Bearer " + token + "x",                        // the token as a prefix
      "Bearer ",
      token,              // no scheme
      "Basic " + token,   // another scheme
      "bearer" + token};  // no space
  for (const std::string& wrong : wrong_ones) {
    SCOPED_TRACE("authorization: " + wrong);
    expect_refused(generate_with(wrong), grpc::StatusCode::UNAUTHENTICATED);
    EXPECT_EQ(list_jobs_with(wrong).error_code(), grpc::StatusCode::UNAUTHENTICATED);
  }
  EXPECT_TRUE(no_jobs()) << "an unauthenticated request reached the queue";
}

TEST_F(BearerTokenTest, RightTokenSucceeds) {
  const std::string authorization = std::string("Bearer ") + kToken;
  expect_meshed(generate_with(authorization));
  EXPECT_TRUE(list_jobs_with(authorization).ok());
}

// Kubernetes probes and load balancers carry no token.
TEST_F(BearerTokenTest, HealthAnswersWithoutToken) {
  auto health = grpc::health::v1::Health::NewStub(server_->channel());
  auto context = context_with_deadline(kRefusalDeadline);
  grpc::health::v1::HealthCheckRequest request;
  grpc::health::v1::HealthCheckResponse response;
  const grpc::Status status = health->Check(context.get(), request, &response);
  ASSERT_TRUE(status.ok()) << status.error_code() << ": " << status.error_message();
  EXPECT_EQ(response.status(), grpc::health::v1::HealthCheckResponse::SERVING);
}

}  // namespace
}  // namespace meshd::testing
