// Reading small files named on a command line (certificates, keys, token files), with errors
// that name the flag they came from.
#pragma once

#include <string>

namespace meshd {

// The whole file. Throws Error(kInvalidArgument) naming `field` when it cannot be read.
std::string read_text_file(const std::string& path, const std::string& field);

// The first line, without surrounding blanks (a token file). Throws Error(kInvalidArgument)
// naming `field` when the file cannot be read or the line is empty.
std::string read_first_line(const std::string& path, const std::string& field);

}  // namespace meshd
