// The server's life: health NOT_SERVING until every worker is warm, SERVING after, NOT_SERVING
// again while it drains; the drain lets running jobs finish within the grace period and cancels
// the rest; the Prometheus endpoint counts a scripted scenario.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <regex>
#include <thread>

#include "grpc/health/v1/health.grpc.pb.h"
#include "tests/server/test_engines.h"
#include "tests/server/test_server.h"

namespace meshd::testing {
namespace {

using namespace std::chrono_literals;
using Health = grpc::health::v1::HealthCheckResponse;

Health::ServingStatus health(const std::string& address) {
  auto stub = grpc::health::v1::Health::NewStub(
      grpc::CreateChannel(address, grpc::InsecureChannelCredentials()));
  grpc::health::v1::HealthCheckRequest request;
  Health response;
  auto context = context_with_deadline(2s);
  if (!stub->Check(context.get(), request, &response).ok()) return Health::UNKNOWN;
  return response.status();
}

TEST(Lifecycle, HealthServesOnlyAfterWarmUpAndStopsServingOnShutdown) {
  auto gate = std::make_shared<Gate>();
  MeshServer server(test_options(), {{"cpu0", Backend::kCpu, gated_cpu_factory(gate, true)}});
  std::thread starting([&] { server.start(); });
  ASSERT_TRUE(eventually([&] { return server.port() != 0; }));
  const std::string address = "127.0.0.1:" + std::to_string(server.port());
  gate->wait_for_waiter();  // the warm-up is held
  EXPECT_EQ(health(address), Health::NOT_SERVING);
  gate->open();
  starting.join();
  EXPECT_EQ(health(address), Health::SERVING);

  // A running job during shutdown: NOT_SERVING and no new jobs while it drains.
  auto stub =
      v1::MeshService::NewStub(grpc::CreateChannel(address, grpc::InsecureChannelCredentials()));
  v1::JobRef ref;
  auto context = context_with_deadline();
  ASSERT_TRUE(stub->Submit(context.get(), endless_request(), &ref).ok());
  const auto job = server.jobs().find(ref.job_id());
  ASSERT_TRUE(eventually([&] { return job->state() == JobState::kRunning; }));
  std::thread stopping([&] { server.shutdown(1s); });
  EXPECT_TRUE(eventually([&] { return health(address) == Health::NOT_SERVING; }, 900ms));
  context = context_with_deadline();
  EXPECT_EQ(stub->Submit(context.get(), disk_request(0.2), &ref).error_code(),
            grpc::StatusCode::UNAVAILABLE);
  stopping.join();
  EXPECT_EQ(job->state(), JobState::kCancelled);  // it outlived the grace period
  EXPECT_EQ(server.jobs().live_jobs(), 0);
}

TEST(Lifecycle, DrainLetsRunningJobsFinishWithinTheGrace) {
  TestServer server;
  auto stub = server.stub();
  StreamResult result;
  std::thread client([&] { result = generate(*stub, disk_request(0.03)); });
  ASSERT_TRUE(eventually([&] { return server.server().jobs().live_jobs() == 1; }));
  server.server().shutdown(30s);
  client.join();
  ASSERT_TRUE(result.status.ok()) << result.status.error_message();
  EXPECT_TRUE(result.has_done);
  EXPECT_TRUE(result.checksum_ok);
}

// GET /metrics over a plain socket.
std::string scrape(int port) {
  const int fd = socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(static_cast<uint16_t>(port));
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  std::string out;
  if (connect(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) == 0) {
    const std::string request =
        "GET /metrics HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n\r\n";
    if (write(fd, request.data(), request.size()) == static_cast<ssize_t>(request.size())) {
      char buffer[4096];
      for (ssize_t n; (n = read(fd, buffer, sizeof buffer)) > 0;) out.append(buffer, n);
    }
  }
  close(fd);
  return out;
}

double metric(const std::string& text, const std::string& name) {
  std::smatch m;
  const std::regex line("(^|\n)" + std::regex_replace(name, std::regex(R"([{}"])"), R"(\$&)") +
                        " ([0-9.e+-]+)");
  return std::regex_search(text, m, line) ? std::stod(m[2]) : -1;
}

TEST(Lifecycle, MetricsEndpointCountsAScriptedScenario) {
  ServerOptions options = test_options();
  options.metrics = "127.0.0.1:0";
  TestServer server(options);
  ASSERT_GT(server.server().metrics_port(), 0);
  auto stub = server.stub();
  ASSERT_TRUE(generate(*stub, disk_request(0.1)).status.ok());
  ASSERT_TRUE(generate(*stub, disk_request(0.05)).status.ok());
  EXPECT_EQ(generate(*stub, disk_request(-1)).status.error_code(),
            grpc::StatusCode::INVALID_ARGUMENT);
  EXPECT_EQ(generate(*stub, endless_request(), 200ms).status.error_code(),
            grpc::StatusCode::DEADLINE_EXCEEDED);
  ASSERT_TRUE(eventually([&] { return server.server().jobs().live_jobs() == 0; }));

  const std::string text = scrape(server.server().metrics_port());
  ASSERT_NE(text.find("200 OK"), std::string::npos) << text;
  EXPECT_EQ(metric(text, R"(meshd_jobs_total{outcome="succeeded"})"), 2);
  EXPECT_EQ(metric(text, R"(meshd_jobs_total{outcome="rejected"})"), 1);
  EXPECT_EQ(metric(text, R"(meshd_jobs_total{outcome="cancelled"})"), 1);
  EXPECT_EQ(metric(text, R"(meshd_jobs_total{outcome="failed"})"), 0);
  EXPECT_EQ(metric(text, R"(meshd_queue_wait_seconds_count{backend="cpu"})"), 3);
  EXPECT_EQ(metric(text, R"(meshd_run_seconds_count{backend="cpu"})"), 3);
  EXPECT_EQ(metric(text, "meshd_live_jobs"), 0);
  EXPECT_EQ(metric(text, "meshd_queue_depth"), 0);
  EXPECT_TRUE(eventually(
      [&] { return metric(scrape(server.server().metrics_port()), "meshd_active_streams") == 0; }));
}

}  // namespace
}  // namespace meshd::testing
