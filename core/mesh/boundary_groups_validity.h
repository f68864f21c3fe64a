// The parts of a validity check that triangle and tetrahedral meshes share: the line format of a
// reported problem, and the checks of boundary_tags and boundary_names, which do not depend on
// what the boundary facets are (edges in 2D, faces in 3D).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace meshd {

// One problem line of a validity report: "<count> <what>; first: <example>".
std::string validity_problem(int64_t count, const std::string& what, const std::string& example);

// The first reason why boundary tags cannot be used to index boundary_names, empty when none:
// #tags != num_facets, or a tag outside [0, num_names). facets names the facets in the message,
// plural ("boundary edges", "boundary faces").
std::string boundary_tags_problem(const std::vector<int32_t>& tags, size_t num_facets,
                                  size_t num_names, const std::string& facets);

struct BoundaryGroupDefects {
  int64_t num_bad_tags = 0;   // tags outside boundary_names, plus |#tags - #facets|
  int64_t num_bad_names = 0;  // empty, repeated or the domain's name
};

// Checks that there is one tag per facet, each in [0, #names), and that the names are non-empty,
// distinct and not kDomainGroupName (writers name physical groups after them, and a repeated name
// would merge or hide a group in every reader that looks groups up by name). Appends one line
// per kind of defect to problems.
//
// tags: #facets group indices; num_facets: #facets; names: #groups; facets: as above.
BoundaryGroupDefects check_boundary_groups(const std::vector<int32_t>& tags, size_t num_facets,
                                           const std::vector<std::string>& names,
                                           const std::string& facets,
                                           std::vector<std::string>& problems);

}  // namespace meshd
