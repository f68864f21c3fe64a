// meshctl: the command-line client of meshd. See meshctl --help and README.md.
#include <cstdio>

#include "client/cli_options.h"
#include "client/commands.h"
#include "client/exit_codes.h"
#include "core/common/error.h"

int main(int argc, char** argv) {
  using namespace meshd::cli;
  CliOptions options;
  try {
    options = parse_cli(std::vector<std::string>(argv + 1, argv + argc));
  } catch (const meshd::Error& e) {
    std::fprintf(stderr, "meshctl: %s\n", e.what());
    return kExitBadRequest;
  }
  if (options.help) {
    std::fputs(help_text(options.command).c_str(), stdout);
    return kExitOk;
  }
  return run_command(options);
}
