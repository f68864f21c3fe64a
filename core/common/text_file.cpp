#include "core/common/text_file.h"

#include <fstream>
#include <sstream>

#include "core/common/error.h"

namespace meshd {

std::string read_text_file(const std::string& path, const std::string& field) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  if (!in || !(s << in.rdbuf())) throw_invalid(field, "cannot read " + path);
  return s.str();
}

std::string read_first_line(const std::string& path, const std::string& field) {
  std::ifstream in(path);
  std::string line;
  if (!in || !std::getline(in, line)) throw_invalid(field, "cannot read " + path);
  const auto first = line.find_first_not_of(" \t\r");
  if (first == std::string::npos) throw_invalid(field, path + " starts with an empty line");
  return line.substr(first, line.find_last_not_of(" \t\r") - first + 1);
}

}  // namespace meshd
