#include "core/mesh/msh41_writer.h"

#include <algorithm>
#include <string>
#include <vector>

#include "core/mesh/msh_physical_names.h"
#include "core/mesh/text_buffer.h"
#include "core/mesh/validity.h"

namespace meshd {
namespace {

constexpr int kSurfaceTag = 1;
constexpr int kLineType = 1;      // 2-node line
constexpr int kTriangleType = 2;  // 3-node triangle

int curve_tag(int group) { return group + 1; }

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
  double min_x = 0, min_y = 0, max_x = 0, max_y = 0;
  bool empty = true;
  void add(Vec2 p) {
    if (empty) {
      min_x = max_x = p.x;
      min_y = max_y = p.y;
      empty = false;
    }
    min_x = std::min(min_x, p.x);
    min_y = std::min(min_y, p.y);
    max_x = std::max(max_x, p.x);
    max_y = std::max(max_y, p.y);
  }
  void write(MshValues& values) const {
    values.real(min_x).real(min_y).real(0.0).real(max_x).real(max_y).real(0.0);
  }
};

}  // namespace

void write_msh41(const Mesh& mesh, std::ostream& out, MshEncoding encoding) {
  check_indices(mesh);
  const int num_groups = static_cast<int>(mesh.boundary_names.size());
  const uint64_t num_points = mesh.points.size();
  const uint64_t num_edges = mesh.boundary_edges.size();
  const uint64_t num_triangles = mesh.triangles.size();

  // Boundary edges bucketed by group (stable, so each group keeps the mesh's order).
  std::vector<std::vector<int64_t>> group_edges(num_groups);
  for (size_t i = 0; i < num_edges; ++i) group_edges[mesh.boundary_tags[i]].push_back(i);

  TextBuffer buffer(out);
  MshValues values(buffer, encoding);

  // $MeshFormat: version, file type, sizeof(size_t); binary adds an int 1 for the byte order.
  buffer.text("$MeshFormat\n4.1 ").number(encoding == MshEncoding::kBinary ? 1 : 0).text(" 8\n");
  if (encoding == MshEncoding::kBinary) buffer.raw(int32_t{1}).character('\n');
  buffer.text("$EndMeshFormat\n");

  // $PhysicalNames is ASCII in both encodings.
  write_msh_physical_names(mesh, buffer);

  // $Entities: no points, one curve per group, one surface bounded by all curves.
  buffer.text("$Entities\n");
  values.size(0).size(num_groups).size(1).size(0).end_line();
  for (int g = 0; g < num_groups; ++g) {
    BoundingBox box;
    for (const int64_t i : group_edges[g]) {
      box.add(mesh.points[mesh.boundary_edges[i][0]]);
      box.add(mesh.points[mesh.boundary_edges[i][1]]);
    }
    values.integer(curve_tag(g));
    box.write(values);
    values.size(1).integer(boundary_physical_tag(g)).size(0).end_line();
  }
  BoundingBox domain_box;
  for (const Vec2 p : mesh.points) domain_box.add(p);
  values.integer(kSurfaceTag);
  domain_box.write(values);
  values.size(1).integer(kDomainPhysicalTag).size(num_groups);
  for (int g = 0; g < num_groups; ++g) values.integer(curve_tag(g));
  values.end_line();
  values.end_section("$EndEntities");

  // $Nodes: one block in the surface; tags first, then coordinates (z = 0).
  buffer.text("$Nodes\n");
  const uint64_t num_node_blocks = num_points > 0 ? 1 : 0;
  values.size(num_node_blocks).size(num_points).size(num_points > 0 ? 1 : 0).size(num_points);
  values.end_line();
  if (num_points > 0) {
    values.integer(2).integer(kSurfaceTag).integer(0).size(num_points).end_line();
    for (uint64_t i = 1; i <= num_points; ++i) values.size(i).end_line();
    for (const Vec2 p : mesh.points) values.real(p.x).real(p.y).real(0.0).end_line();
  }
  values.end_section("$EndNodes");

  // $Elements: one block of lines per non-empty group, then the triangles.
  buffer.text("$Elements\n");
  uint64_t num_blocks = num_triangles > 0 ? 1 : 0;
  for (const auto& edges : group_edges) num_blocks += edges.empty() ? 0 : 1;
  const uint64_t num_elements = num_edges + num_triangles;
  values.size(num_blocks).size(num_elements).size(num_elements > 0 ? 1 : 0).size(num_elements);
  values.end_line();
  uint64_t tag = 1;
  for (int g = 0; g < num_groups; ++g) {
    if (group_edges[g].empty()) continue;
    values.integer(1).integer(curve_tag(g)).integer(kLineType).size(group_edges[g].size());
    values.end_line();
    for (const int64_t i : group_edges[g]) {
      const auto& e = mesh.boundary_edges[i];
      values.size(tag++).size(uint64_t(e[0]) + 1).size(uint64_t(e[1]) + 1).end_line();
    }
  }
  if (num_triangles > 0) {
    values.integer(2).integer(kSurfaceTag).integer(kTriangleType).size(num_triangles).end_line();
    for (const auto& t : mesh.triangles) {
      values.size(tag++);
      for (const int32_t v : t) values.size(uint64_t(v) + 1);
      values.end_line();
    }
  }
  values.end_section("$EndElements");
}

}  // namespace meshd
