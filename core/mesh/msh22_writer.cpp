#include "core/mesh/msh22_writer.h"

#include <algorithm>
#include <string>

#include "core/mesh/mesh_cells.h"
#include "core/mesh/msh_physical_names.h"
#include "core/mesh/text_buffer.h"
#include "core/mesh/validity.h"
#include "core/mesh3d/tet_validity.h"

namespace meshd {
namespace {

// The elementary entity of the cells (a surface in 2D, a volume in 3D); a boundary group g's is
// g + 1, as in the MSH 4.1 writer.
constexpr int kDomainEntityTag = 1;

template <typename M>
void write_msh22_cells(const M& mesh, std::ostream& out) {
  using Cells = MeshCells<M>;
  check_indices(mesh);
  const auto& cells = Cells::cells(mesh);
  const auto& facets = Cells::facets(mesh);
  const int num_groups = static_cast<int>(mesh.boundary_names.size());
  TextBuffer b(out);

  b.text("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n");

  write_msh_physical_names(mesh.boundary_names, Cells::kDimension, b);

  b.text("$Nodes\n").number(mesh.points.size()).character('\n');
  for (size_t i = 0; i < mesh.points.size(); ++i) {
    const Vec3 p = Cells::point(mesh, i);
    b.number(i + 1).character(' ').number(p.x).character(' ').number(p.y).character(' ');
    if (Cells::kDimension == 2)
      b.character('0');  // as the 2D files always had it
    else
      b.number(p.z);
    b.character('\n');
  }
  b.text("$EndNodes\n");

  // Facets grouped by boundary group, as the MSH 4.1 writer orders them, so that element numbers
  // agree between the two formats.
  b.text("$Elements\n").number(facets.size() + cells.size());
  b.character('\n');
  int64_t number = 1;
  for (int g = 0; g < num_groups; ++g) {
    for (size_t i = 0; i < facets.size(); ++i) {
      if (mesh.boundary_tags[i] != g) continue;
      b.number(number++).character(' ').number(Cells::kMshFacet).text(" 2 ");
      b.number(boundary_physical_tag(g)).character(' ').number(g + 1);
      for (const int32_t v : facets[i]) b.character(' ').number(int64_t{v} + 1);
      b.character('\n');
    }
  }
  for (const auto& c : cells) {
    b.number(number++).character(' ').number(Cells::kMshCell).text(" 2 ");
    b.number(kDomainPhysicalTag).character(' ').number(kDomainEntityTag);
    for (const int32_t v : c) b.character(' ').number(int64_t{v} + 1);
    b.character('\n');
  }
  b.text("$EndElements\n");
}

}  // namespace

void write_msh22(const Mesh& mesh, std::ostream& out) { write_msh22_cells(mesh, out); }

void write_msh22(const TetMesh& mesh, std::ostream& out) { write_msh22_cells(mesh, out); }

}  // namespace meshd
