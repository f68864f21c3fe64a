// The $PhysicalNames section, the same in MSH 2.2 and 4.1 (ASCII in both 4.1 encodings): the
// domain (the mesh's dimension) and one boundary group per name (one dimension less), numbered
// as mesh.h says.
#pragma once

#include <algorithm>
#include <string>
#include <vector>

#include "core/mesh/physical_groups.h"
#include "core/mesh/text_buffer.h"

namespace meshd {

// Names go between double quotes and MSH has no escapes, so a quote would end the name early.
inline std::string msh_quoted(const std::string& name) {
  std::string s = name;
  std::replace_if(
      s.begin(), s.end(), [](char c) { return c == '"' || c == '\n' || c == '\r'; }, '_');
  return "\"" + s + "\"";
}

// boundary_names: one per boundary group; dimension: 2 for triangles, 3 for tetrahedra.
inline void write_msh_physical_names(const std::vector<std::string>& boundary_names, int dimension,
                                     TextBuffer& b) {
  const int num_groups = static_cast<int>(boundary_names.size());
  b.text("$PhysicalNames\n").number(num_groups + 1).character('\n');
  b.number(dimension).character(' ').number(kDomainPhysicalTag).character(' ');
  b.text(msh_quoted(kDomainGroupName)).character('\n');
  for (int g = 0; g < num_groups; ++g) {
    b.number(dimension - 1).character(' ').number(boundary_physical_tag(g)).character(' ');
    b.text(msh_quoted(boundary_names[g])).character('\n');
  }
  b.text("$EndPhysicalNames\n");
}

}  // namespace meshd
