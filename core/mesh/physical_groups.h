// Physical group numbering shared by every writer and by both kinds of mesh (mesh.h, tet_mesh.h):
// the domain is group 1 of the mesh's dimension (2 for triangles, 3 for tetrahedra), boundary
// group i is i + 2 of one dimension less. Distinct numbers across dimensions keep tools that
// ignore the dimension happy.
#pragma once

namespace meshd {

constexpr int kDomainPhysicalTag = 1;
inline int boundary_physical_tag(int group) { return group + 2; }
constexpr const char* kDomainGroupName = "domain";

}  // namespace meshd
