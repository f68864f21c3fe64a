#include "core/mesh/boundary_groups_validity.h"

#include <cstdlib>
#include <set>
#include <sstream>

#include "core/mesh/physical_groups.h"

namespace meshd {

std::string validity_problem(int64_t count, const std::string& what, const std::string& example) {
  std::ostringstream s;
  s << count << " " << what << "; first: " << example;
  return s.str();
}

std::string boundary_tags_problem(const std::vector<int32_t>& tags, size_t num_facets,
                                  size_t num_names, const std::string& facets) {
  if (tags.size() != num_facets) {
    return "boundary_tags has " + std::to_string(tags.size()) + " entries for " +
           std::to_string(num_facets) + " " + facets;
  }
  for (size_t i = 0; i < tags.size(); ++i) {
    if (tags[i] < 0 || static_cast<size_t>(tags[i]) >= num_names) {
      return "boundary_tags[" + std::to_string(i) + "] = " + std::to_string(tags[i]) +
             " is outside [0, " + std::to_string(num_names) + ")";
    }
  }
  return "";
}

BoundaryGroupDefects check_boundary_groups(const std::vector<int32_t>& tags, size_t num_facets,
                                           const std::vector<std::string>& names,
                                           const std::string& facets,
                                           std::vector<std::string>& problems) {
  BoundaryGroupDefects defects;
  const size_t num_groups = names.size();
  if (tags.size() != num_facets) {
    defects.num_bad_tags =
        std::abs(static_cast<int64_t>(tags.size()) - static_cast<int64_t>(num_facets));
    problems.push_back("boundary_tags has " + std::to_string(tags.size()) + " entries for " +
                       std::to_string(num_facets) + " " + facets);
  }
  int64_t out_of_range_tags = 0;
  std::string first;
  for (size_t i = 0; i < tags.size(); ++i) {
    const int32_t tag = tags[i];
    if (tag >= 0 && static_cast<size_t>(tag) < num_groups) continue;
    if (out_of_range_tags++ == 0) {
      first = "boundary_tags[" + std::to_string(i) + "] = " + std::to_string(tag);
    }
  }
  if (out_of_range_tags > 0) {
    defects.num_bad_tags += out_of_range_tags;
    problems.push_back(validity_problem(
        out_of_range_tags,
        "boundary tags are outside [0, " + std::to_string(num_groups) + ") (#boundary_names)",
        first));
  }

  std::set<std::string> seen;
  for (size_t i = 0; i < num_groups; ++i) {
    const std::string& name = names[i];
    if (!name.empty() && name != kDomainGroupName && seen.insert(name).second) continue;
    if (defects.num_bad_names++ == 0) {
      first = "boundary_names[" + std::to_string(i) + "] = \"" + name + "\"";
    }
  }
  if (defects.num_bad_names > 0) {
    problems.push_back(validity_problem(
        defects.num_bad_names,
        "boundary group names are empty, repeated or \"" + std::string(kDomainGroupName) + "\"",
        first));
  }
  return defects;
}

}  // namespace meshd
