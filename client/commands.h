// meshctl's commands, each returning its exit code (exit_codes.h).
#pragma once

#include "client/cli_options.h"

namespace meshd::cli {

int run_command(const CliOptions& options);

}  // namespace meshd::cli
