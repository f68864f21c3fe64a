// The $PhysicalNames section, the same in MSH 2.2 and 4.1 (ASCII in both 4.1 encodings): the
// domain (dimension 2) and one boundary group per name (dimension 1), numbered as mesh.h says.
#pragma once

#include <algorithm>
#include <string>

#include "core/mesh/mesh.h"
#include "core/mesh/text_buffer.h"

namespace meshd {

// Names go between double quotes and MSH has no escapes, so a quote would end the name early.
inline std::string msh_quoted(const std::string& name) {
  std::string s = name;
  std::replace_if(
      s.begin(), s.end(), [](char c) { return c == '"' || c == '\n' || c == '\r'; }, '_');
  return "\"" + s + "\"";
}

inline void write_msh_physical_names(const Mesh& mesh, TextBuffer& b) {
  const int num_groups = static_cast<int>(mesh.boundary_names.size());
  b.text("$PhysicalNames\n").number(num_groups + 1).character('\n');
  b.text("2 ").number(kDomainPhysicalTag).character(' ').text(msh_quoted(kDomainGroupName));
  b.character('\n');
  for (int g = 0; g < num_groups; ++g) {
    b.text("1 ").number(boundary_physical_tag(g)).character(' ');
    b.text(msh_quoted(mesh.boundary_names[g])).character('\n');
  }
  b.text("$EndPhysicalNames\n");
}

}  // namespace meshd
