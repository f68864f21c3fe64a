#include "core/mesh/msh41_writer.h"

#include <algorithm>
#include <string>
#include <vector>

#include "core/mesh/mesh_cells.h"
#include "core/mesh/msh_physical_names.h"
#include "core/mesh/text_buffer.h"
#include "core/mesh/validity.h"
#include "core/mesh3d/tet_validity.h"

namespace meshd {
namespace {

// The entity that holds the cells and the nodes (a surface in 2D, a volume in 3D), and the one
// of each boundary group (curves in 2D, surfaces in 3D).
constexpr int kDomainEntityTag = 1;
int facet_entity_tag(int group) { return group + 1; }

// Writes the values of the sections after $PhysicalNames, in either encoding: ASCII separates
// values by spaces and ends lines where end_line() is called; binary writes the bytes of each
// value (size_t as uint64_t, as the header's data-size 8 promises) and ignores line ends. One
// sequence of calls therefore produces both encodings.
class MshValues {
 public:
  MshValues(TextBuffer& buffer, MshEncoding encoding)
      : buffer_(buffer), binary_(encoding == MshEncoding::kBinary) {}

  MshValues& size(uint64_t v) { return binary_ ? raw(v) : ascii(v); }
  MshValues& integer(int32_t v) { return binary_ ? raw(v) : ascii(v); }
  MshValues& real(double v) { return binary_ ? raw(v) : ascii(v); }
  void end_line() {
    if (!binary_) buffer_.character('\n');
    first_on_line_ = true;
  }
  // Closes a section: binary data is followed by a newline, then the end marker.
  void end_section(const char* end_marker) {
    if (binary_) buffer_.character('\n');
    buffer_.text(end_marker).character('\n');
  }

 private:
  template <typename T>
  MshValues& raw(T v) {
    buffer_.raw(v);
    return *this;
  }
  template <typename T>
  MshValues& ascii(T v) {
    if (!first_on_line_) buffer_.character(' ');
    buffer_.number(v);
    first_on_line_ = false;
    return *this;
  }

  TextBuffer& buffer_;
  bool binary_;
  bool first_on_line_ = true;
};

struct BoundingBox {
  Vec3 min, max;
  bool empty = true;
  void add(Vec3 p) {
    if (empty) {
      min = max = p;
      empty = false;
    }
    min = {std::min(min.x, p.x), std::min(min.y, p.y), std::min(min.z, p.z)};
    max = {std::max(max.x, p.x), std::max(max.y, p.y), std::max(max.z, p.z)};
  }
  void write(MshValues& values) const {
    values.real(min.x).real(min.y).real(min.z).real(max.x).real(max.y).real(max.z);
  }
};

template <typename M>
void write_msh41_cells(const M& mesh, std::ostream& out, MshEncoding encoding) {
  using Cells = MeshCells<M>;
  constexpr int kDim = Cells::kDimension;
  check_indices(mesh);
  const auto& cells = Cells::cells(mesh);
  const auto& facets = Cells::facets(mesh);
  const int num_groups = static_cast<int>(mesh.boundary_names.size());
  const uint64_t num_points = mesh.points.size();
  const uint64_t num_facets = facets.size();
  const uint64_t num_cells = cells.size();

  // Boundary facets bucketed by group (stable, so each group keeps the mesh's order).
  std::vector<std::vector<int64_t>> group_facets(num_groups);
  for (size_t i = 0; i < num_facets; ++i) group_facets[mesh.boundary_tags[i]].push_back(i);

  TextBuffer buffer(out);
  MshValues values(buffer, encoding);

  // $MeshFormat: version, file type, sizeof(size_t); binary adds an int 1 for the byte order.
  buffer.text("$MeshFormat\n4.1 ").number(encoding == MshEncoding::kBinary ? 1 : 0).text(" 8\n");
  if (encoding == MshEncoding::kBinary) buffer.raw(int32_t{1}).character('\n');
  buffer.text("$EndMeshFormat\n");

  // $PhysicalNames is ASCII in both encodings.
  write_msh_physical_names(mesh.boundary_names, kDim, buffer);

  // $Entities: no points; one entity of dimension kDim - 1 per group, one of dimension kDim
  // bounded by all of them. The counts are of points, curves, surfaces and volumes.
  buffer.text("$Entities\n");
  for (int d = 0; d <= 3; ++d) values.size(d == kDim - 1 ? num_groups : d == kDim ? 1 : 0);
  values.end_line();
  for (int g = 0; g < num_groups; ++g) {
    BoundingBox box;
    for (const int64_t i : group_facets[g])
      for (const int32_t v : facets[i]) box.add(Cells::point(mesh, v));
    values.integer(facet_entity_tag(g));
    box.write(values);
    values.size(1).integer(boundary_physical_tag(g)).size(0).end_line();
  }
  BoundingBox domain_box;
  for (size_t i = 0; i < num_points; ++i) domain_box.add(Cells::point(mesh, i));
  values.integer(kDomainEntityTag);
  domain_box.write(values);
  values.size(1).integer(kDomainPhysicalTag).size(num_groups);
  for (int g = 0; g < num_groups; ++g) values.integer(facet_entity_tag(g));
  values.end_line();
  values.end_section("$EndEntities");

  // $Nodes: one block in the domain's entity; tags first, then coordinates.
  buffer.text("$Nodes\n");
  const uint64_t num_node_blocks = num_points > 0 ? 1 : 0;
  values.size(num_node_blocks).size(num_points).size(num_points > 0 ? 1 : 0).size(num_points);
  values.end_line();
  if (num_points > 0) {
    values.integer(kDim).integer(kDomainEntityTag).integer(0).size(num_points).end_line();
    for (uint64_t i = 1; i <= num_points; ++i) values.size(i).end_line();
    for (size_t i = 0; i < num_points; ++i) {
      const Vec3 p = Cells::point(mesh, i);
      values.real(p.x).real(p.y).real(p.z).end_line();
    }
  }
  values.end_section("$EndNodes");

  // $Elements: one block of facets per non-empty group, then the cells.
  buffer.text("$Elements\n");
  uint64_t num_blocks = num_cells > 0 ? 1 : 0;
  for (const auto& group : group_facets) num_blocks += group.empty() ? 0 : 1;
  const uint64_t num_elements = num_facets + num_cells;
  values.size(num_blocks).size(num_elements).size(num_elements > 0 ? 1 : 0).size(num_elements);
  values.end_line();
  uint64_t tag = 1;
  for (int g = 0; g < num_groups; ++g) {
    if (group_facets[g].empty()) continue;
    values.integer(kDim - 1).integer(facet_entity_tag(g)).integer(Cells::kMshFacet);
    values.size(group_facets[g].size()).end_line();
    for (const int64_t i : group_facets[g]) {
      values.size(tag++);
      for (const int32_t v : facets[i]) values.size(uint64_t(v) + 1);
      values.end_line();
    }
  }
  if (num_cells > 0) {
    values.integer(kDim).integer(kDomainEntityTag).integer(Cells::kMshCell).size(num_cells);
    values.end_line();
    for (const auto& c : cells) {
      values.size(tag++);
      for (const int32_t v : c) values.size(uint64_t(v) + 1);
      values.end_line();
    }
  }
  values.end_section("$EndElements");
}

}  // namespace

void write_msh41(const Mesh& mesh, std::ostream& out, MshEncoding encoding) {
  write_msh41_cells(mesh, out, encoding);
}

void write_msh41(const TetMesh& mesh, std::ostream& out, MshEncoding encoding) {
  write_msh41_cells(mesh, out, encoding);
}

}  // namespace meshd
