// meshd's command line and config file: defaults, every flag, the file with the command line
// winning, and bad values refused naming the flag.
#include "server/server_options.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>

#include "core/common/error.h"

namespace meshd::testing {
namespace {

ServerOptions parse(const std::vector<std::string>& args) {
  bool help = false;
  return parse_server_options(args, help);
}

// The flag an invalid command line is refused for.
std::string refused_flag(const std::vector<std::string>& args) {
  try {
    parse(args);
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::kInvalidArgument);
    return e.field();
  }
  return "(accepted)";
}

TEST(ServerOptions, DefaultsAreTheDocumentedOnes) {
  const ServerOptions o = parse({});
  EXPECT_EQ(o.listen, "127.0.0.1:50051");
  EXPECT_EQ(o.metrics, "");
  EXPECT_EQ(o.backend, Backend::kAuto);
  EXPECT_EQ(o.gpu_workers, 4);
  EXPECT_EQ(o.cpu_workers, 1);
  EXPECT_EQ(o.jobs.queue_capacity, 64u);
  EXPECT_EQ(o.jobs.retention, std::chrono::minutes(10));
  EXPECT_EQ(o.drain_timeout_s, 30);
  EXPECT_EQ(o.jobs.limits.max_nodes, 5'000'000);
  EXPECT_EQ(o.jobs.limits.max_snapshot_nodes, 50'000);
}

TEST(ServerOptions, FlagsAndTheirEqualsForm) {
  const ServerOptions o = parse({"--listen",
                                 "0.0.0.0:0",
                                 "--metrics=127.0.0.1:9464",
                                 "--backend",
                                 "cpu",
                                 "--gpu-workers",
                                 "2",
                                 "--cpu-workers",
                                 "3",
                                 "--cpu-threads=2",
                                 "--queue-capacity",
                                 "5",
                                 "--retention",
                                 "1.5",
                                 "--max-retained",
                                 "7",
                                 "--drain-timeout",
                                 "4",
                                 "--max-nodes",
                                 "1000",
                                 "--max-snapshot-nodes",
                                 "10",
                                 "--max-grid-samples",
                                 "4096",
                                 "--max-size-grid-values",
                                 "2500",
                                 "--log-level",
                                 "debug"});
  EXPECT_EQ(o.listen, "0.0.0.0:0");
  EXPECT_EQ(o.metrics, "127.0.0.1:9464");
  EXPECT_EQ(o.backend, Backend::kCpu);
  EXPECT_EQ(o.gpu_workers, 2);
  EXPECT_EQ(o.cpu_workers, 3);
  EXPECT_EQ(o.cpu_threads, 2u);
  EXPECT_EQ(o.jobs.queue_capacity, 5u);
  EXPECT_EQ(o.jobs.retention, std::chrono::milliseconds(1500));
  EXPECT_EQ(o.jobs.max_retained, 7u);
  EXPECT_EQ(o.drain_timeout_s, 4);
  EXPECT_EQ(o.jobs.limits.max_nodes, 1000);
  EXPECT_EQ(o.jobs.limits.max_snapshot_nodes, 10);
  EXPECT_EQ(o.jobs.limits.max_grid_samples, 4096);
  EXPECT_EQ(o.jobs.limits.max_size_grid_values, 2500);
  EXPECT_EQ(o.log_level, "debug");
}

TEST(ServerOptions, ConfigFileThenCommandLine) {
  const std::string path = ::testing::TempDir() + "meshd_test.conf";
  {
    std::ofstream f(path);
    f << "# a comment\n\nlisten = 127.0.0.1:6000\nqueue-capacity = 9   # trailing\n"
         "backend=cpu\n";
  }
  const ServerOptions o = parse({"--config", path, "--queue-capacity", "11"});
  EXPECT_EQ(o.listen, "127.0.0.1:6000");
  EXPECT_EQ(o.backend, Backend::kCpu);
  EXPECT_EQ(o.jobs.queue_capacity, 11u);  // the command line wins
  {
    std::ofstream f(path);
    f << "queue-capacity 9\n";
  }
  EXPECT_EQ(refused_flag({"--config", path}), "--config");
  {
    std::ofstream f(path);
    f << "no-such-flag = 1\n";
  }
  EXPECT_EQ(refused_flag({"--config", path}), "--no-such-flag");
  std::remove(path.c_str());
  EXPECT_EQ(refused_flag({"--config", path}), "--config");
}

TEST(ServerOptions, BadValuesNameTheFlag) {
  EXPECT_EQ(refused_flag({"--backend", "tpu"}), "--backend");
  EXPECT_EQ(refused_flag({"--gpu-workers", "0"}), "--gpu-workers");
  EXPECT_EQ(refused_flag({"--gpu-workers", "65"}), "--gpu-workers");
  EXPECT_EQ(refused_flag({"--cpu-workers", "0"}), "--cpu-workers");
  EXPECT_EQ(refused_flag({"--cpu-workers", "1.5"}), "--cpu-workers");
  EXPECT_EQ(refused_flag({"--queue-capacity", "many"}), "--queue-capacity");
  EXPECT_EQ(refused_flag({"--retention", "-1"}), "--retention");
  EXPECT_EQ(refused_flag({"--max-snapshot-nodes", "1000000"}), "--max-snapshot-nodes");
  EXPECT_EQ(refused_flag({"--max-grid-samples", "3"}), "--max-grid-samples");
  EXPECT_EQ(refused_flag({"--log-level", "loud"}), "--log-level");
  EXPECT_EQ(refused_flag({"--listen"}), "--listen");
  EXPECT_EQ(refused_flag({"--bogus", "1"}), "--bogus");
  EXPECT_EQ(refused_flag({"stray"}), "stray");
  EXPECT_EQ(refused_flag({"--tls-cert", "c.pem"}), "--tls-cert");  // needs --tls-key
  EXPECT_EQ(refused_flag({"--tls-client-ca", "ca.pem"}), "--tls-client-ca");
  bool help = false;
  parse_server_options({"--help"}, help);
  EXPECT_TRUE(help);
}

TEST(ServerOptions, CpuBackendMakesOnlyCpuWorkers) {
  ServerOptions o = parse({"--backend", "cpu", "--cpu-workers", "2"});
  const auto workers = workers_for(o);
  ASSERT_EQ(workers.size(), 2u);
  for (const auto& w : workers) EXPECT_EQ(w.kind, Backend::kCpu);
}

}  // namespace
}  // namespace meshd::testing
