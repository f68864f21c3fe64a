// meshd's settings: command-line flags, and an optional config file of the same names.
#pragma once

#include <string>
#include <vector>

#include "server/job_manager.h"

namespace meshd {

struct ServerOptions {
  std::string listen = "127.0.0.1:50051";  // port 0 picks a free port
  std::string metrics;                     // HOST:PORT for /metrics; empty: none
  Backend backend = Backend::kAuto;        // kCpu: no GPU workers; kGpu: refuse to start without
  // Per visible device. Small jobs are latency-bound: on an H100, 4 workers serve 2.9x the
  // ~2k-node jobs of one, 8 workers 4.2x, 16 no more (bench/RESULTS.md).
  int gpu_workers = 4;
  int cpu_workers = 1;
  int max_request_mb = 256;  // largest request message; gRPC's own default is 4 MiB
  unsigned cpu_threads = 0;  // per CPU worker; 0: the cores shared among the CPU workers
  double drain_timeout_s = 30;
  JobManagerOptions jobs;
  std::string tls_cert, tls_key;  // PEM files; both or neither
  std::string tls_client_ca;      // PEM file: require client certificates signed by it
  std::string token_file;         // bearer token; empty: no token check
  std::string log_level = "info";
};

// Parses meshd's command line. `--config FILE` reads "name = value" lines (the flag names
// without "--", '#' comments) first; flags on the command line win. Throws
// Error(kInvalidArgument) naming the flag and its allowed values; sets `help` on --help.
ServerOptions parse_server_options(const std::vector<std::string>& args, bool& help);

// The --help text.
const char* server_usage();

// gpu_workers GPU workers per visible device (unless --backend cpu) and the CPU workers. Throws
// Error(kUnavailable) for --backend gpu on a machine without a GPU.
std::vector<WorkerSpec> workers_for(const ServerOptions& options);

}  // namespace meshd
