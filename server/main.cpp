// meshd: the mesh service. See meshd --help and README.md.
#include <pthread.h>
#include <spdlog/spdlog.h>

#include <csignal>
#include <cstdio>

#include "core/common/error.h"
#include "server/mesh_server.h"

int main(int argc, char** argv) {
  bool help = false;
  meshd::ServerOptions options;
  try {
    options = meshd::parse_server_options(std::vector<std::string>(argv + 1, argv + argc), help);
  } catch (const meshd::Error& e) {
    std::fprintf(stderr, "meshd: %s\n", e.what());
    return 2;
  }
  if (help) {
    std::fputs(meshd::server_usage(), stdout);
    return 0;
  }
  spdlog::set_level(spdlog::level::from_str(options.log_level));
  spdlog::set_pattern("%Y-%m-%dT%H:%M:%S.%e %^%l%$ %v");

  // Block the stop signals in every thread; the main thread waits for them below.
  sigset_t stop_signals;
  sigemptyset(&stop_signals);
  sigaddset(&stop_signals, SIGTERM);
  sigaddset(&stop_signals, SIGINT);
  pthread_sigmask(SIG_BLOCK, &stop_signals, nullptr);

  try {
    meshd::MeshServer server(options);
    server.start();
    int signal = 0;
    sigwait(&stop_signals, &signal);
    spdlog::info("received {}", signal == SIGTERM ? "SIGTERM" : "SIGINT");
    server.shutdown(
        std::chrono::milliseconds(static_cast<int64_t>(1000 * options.drain_timeout_s)));
  } catch (const std::exception& e) {
    spdlog::error("meshd: {}", e.what());
    return 1;
  }
  return 0;
}
