// The request meshctl sends: a text-format file, or the simple-shape flags, with the job option
// flags applied on top.
#pragma once

#include "client/cli_options.h"
#include "meshd/v1/request.pb.h"

namespace meshd::cli {

// Throws Error(kInvalidArgument) naming the flag or "request" when neither a file nor a shape
// flag is given, or both.
v1::MeshRequest build_request(const CliOptions& options);

}  // namespace meshd::cli
