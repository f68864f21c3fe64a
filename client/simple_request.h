// The request meshctl sends: a text-format file, the simple-shape flags or an imported outline
// (--import), or a signed-distance grid (--sdf-grid), with the job option flags applied on top.
#pragma once

#include <string>

#include "client/cli_options.h"
#include "meshd/v1/request.pb.h"

namespace meshd::cli {

// Throws Error(kInvalidArgument) naming the flag or "request" when neither a file nor a shape
// flag nor --import nor --sdf-grid is given, or a combination that does not fit (see meshctl help
// generate). With --import, `import_summary` (when given) receives one line on what was imported.
v1::MeshRequest build_request(const CliOptions& options, std::string* import_summary = nullptr);

}  // namespace meshd::cli
