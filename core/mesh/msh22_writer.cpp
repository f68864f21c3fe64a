#include "core/mesh/msh22_writer.h"

#include <algorithm>
#include <string>

#include "core/mesh/msh_physical_names.h"
#include "core/mesh/text_buffer.h"
#include "core/mesh/validity.h"

namespace meshd {
namespace {

constexpr int kLineType = 1;
constexpr int kTriangleType = 2;
constexpr int kSurfaceTag = 1;

}  // namespace

void write_msh22(const Mesh& mesh, std::ostream& out) {
  check_indices(mesh);
  const int num_groups = static_cast<int>(mesh.boundary_names.size());
  TextBuffer b(out);

  b.text("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n");

  write_msh_physical_names(mesh, b);

  b.text("$Nodes\n").number(mesh.points.size()).character('\n');
  for (size_t i = 0; i < mesh.points.size(); ++i) {
    b.number(i + 1).character(' ').number(mesh.points[i].x).character(' ');
    b.number(mesh.points[i].y).text(" 0\n");
  }
  b.text("$EndNodes\n");

  // Lines grouped by boundary group, as the MSH 4.1 writer orders them, so that element numbers
  // agree between the two formats.
  b.text("$Elements\n").number(mesh.boundary_edges.size() + mesh.triangles.size());
  b.character('\n');
  int64_t number = 1;
  for (int g = 0; g < num_groups; ++g) {
    for (size_t i = 0; i < mesh.boundary_edges.size(); ++i) {
      if (mesh.boundary_tags[i] != g) continue;
      const auto& e = mesh.boundary_edges[i];
      b.number(number++).character(' ').number(kLineType).text(" 2 ");
      b.number(boundary_physical_tag(g)).character(' ').number(g + 1).character(' ');
      b.number(int64_t{e[0]} + 1).character(' ').number(int64_t{e[1]} + 1).character('\n');
    }
  }
  for (const auto& t : mesh.triangles) {
    b.number(number++).character(' ').number(kTriangleType).text(" 2 ");
    b.number(kDomainPhysicalTag).character(' ').number(kSurfaceTag);
    for (const int32_t v : t) b.character(' ').number(int64_t{v} + 1);
    b.character('\n');
  }
  b.text("$EndElements\n");
}

}  // namespace meshd
