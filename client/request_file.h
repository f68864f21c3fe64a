// Reading a MeshRequest written in protobuf text format, the format of examples/*.textproto and
// of meshctl's request files.
#pragma once

#include <string>

#include "meshd/v1/request.pb.h"

namespace meshd {

// Parses the text-format MeshRequest in the file at `path`. Throws Error(kInvalidArgument,
// "request", ...) when the file cannot be read ("cannot open 'x.textproto': No such file or
// directory") or does not parse ("x.textproto:3:14: Expected identifier, got: }"; lines and
// columns count from 1). Values are not validated here: that is to_problem's job.
v1::MeshRequest read_request_file(const std::string& path);

// The same for text already in memory; `source` names it in messages (a path, "<stdin>").
v1::MeshRequest parse_request_text(const std::string& text, const std::string& source);

}  // namespace meshd
