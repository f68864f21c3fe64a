#include "core/mesh/vtu_writer.h"

#include <bit>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "core/mesh/mesh_cells.h"
#include "core/mesh/text_buffer.h"
#include "core/mesh/validity.h"
#include "core/mesh/xml_escaped.h"
#include "core/mesh3d/tet_validity.h"

namespace meshd {
namespace {

// ---- Base64 (RFC 4648, with padding) -----------------------------------------------------------

// Encodes a byte stream in pieces; finish() writes the last, padded quantum.
class Base64Encoder {
 public:
  explicit Base64Encoder(TextBuffer& out) : out_(out) {}

  void add(const void* data, size_t size) {
    const auto* bytes = static_cast<const uint8_t*>(data);
    for (size_t i = 0; i < size; ++i) {
      pending_[num_pending_++] = bytes[i];
      if (num_pending_ == 3) emit(3);
    }
  }
  void finish() {
    if (num_pending_ > 0) emit(num_pending_);
  }

 private:
  static constexpr char kAlphabet[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

  // Writes the pending bytes (1 to 3) as four characters, '=' standing for the missing ones.
  void emit(int n) {
    const uint32_t b0 = pending_[0], b1 = n > 1 ? pending_[1] : 0, b2 = n > 2 ? pending_[2] : 0;
    const uint32_t triple = (b0 << 16) | (b1 << 8) | b2;
    char quad[4] = {kAlphabet[(triple >> 18) & 63], kAlphabet[(triple >> 12) & 63],
                    n > 1 ? kAlphabet[(triple >> 6) & 63] : '=',
                    n > 2 ? kAlphabet[triple & 63] : '='};
    out_.text(std::string_view(quad, 4));
    num_pending_ = 0;
  }

  TextBuffer& out_;
  uint8_t pending_[3] = {0, 0, 0};
  int num_pending_ = 0;
};

// ---- DataArray elements -------------------------------------------------------------------------

template <typename T>
const char* vtk_type_name();
template <>
const char* vtk_type_name<double>() {
  return "Float64";
}
template <>
const char* vtk_type_name<int64_t>() {
  return "Int64";
}
template <>
const char* vtk_type_name<int32_t>() {
  return "Int32";
}
template <>
const char* vtk_type_name<uint8_t>() {
  return "UInt8";
}

// Writes one <DataArray> with its values base64-encoded behind a UInt64 byte count.
// extra_attributes goes verbatim into the start tag (NumberOfComponents and the like).
template <typename T>
void write_data_array(TextBuffer& b, const std::string& name, const std::vector<T>& values,
                      const std::string& extra_attributes = "") {
  b.text("        <DataArray type=\"").text(vtk_type_name<T>()).text("\" Name=\"");
  b.text(xml_escaped(name)).text("\"").text(extra_attributes).text(" format=\"binary\">\n");
  b.text("          ");
  Base64Encoder encoder(b);
  const uint64_t num_bytes = values.size() * sizeof(T);
  encoder.add(&num_bytes, sizeof(num_bytes));
  encoder.add(values.data(), num_bytes);
  encoder.finish();
  b.text("\n        </DataArray>\n");
}

template <typename M>
void write_vtu_cells(const M& mesh, std::ostream& out) {
  using Cells = MeshCells<M>;
  check_indices(mesh);
  const auto& cells = Cells::cells(mesh);
  const auto& facets = Cells::facets(mesh);
  const size_t num_interior = cells.size();
  const size_t num_facets = facets.size();
  const size_t num_cells = num_interior + num_facets;
  const double nan = std::numeric_limits<double>::quiet_NaN();

  TextBuffer b(out);
  b.text("<?xml version=\"1.0\"?>\n");
  b.text("<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"");
  b.text(std::endian::native == std::endian::little ? "LittleEndian" : "BigEndian");
  b.text("\" header_type=\"UInt64\">\n  <UnstructuredGrid>\n");

  b.text("    <FieldData>\n");
  const std::string tag_dim = " NumberOfTuples=\"1\" NumberOfComponents=\"2\"";
  write_data_array(b, kDomainGroupName, std::vector<int32_t>{kDomainPhysicalTag, Cells::kDimension},
                   tag_dim);
  for (size_t g = 0; g < mesh.boundary_names.size(); ++g) {
    const std::vector<int32_t> value{boundary_physical_tag(static_cast<int>(g)),
                                     Cells::kDimension - 1};
    write_data_array(b, mesh.boundary_names[g], value, tag_dim);
  }
  b.text("    </FieldData>\n");

  b.text("    <Piece NumberOfPoints=\"").number(mesh.points.size());
  b.text("\" NumberOfCells=\"").number(num_cells).text("\">\n");

  b.text("      <Points>\n");
  std::vector<double> xyz;
  xyz.reserve(3 * mesh.points.size());
  for (size_t i = 0; i < mesh.points.size(); ++i) {
    const Vec3 p = Cells::point(mesh, i);
    xyz.insert(xyz.end(), {p.x, p.y, p.z});
  }
  write_data_array(b, "Points", xyz, " NumberOfComponents=\"3\"");
  xyz = {};
  b.text("      </Points>\n");

  b.text("      <Cells>\n");
  std::vector<int64_t> connectivity, offsets;
  std::vector<uint8_t> types;
  offsets.reserve(num_cells);
  types.reserve(num_cells);
  for (const auto& c : cells) {
    connectivity.insert(connectivity.end(), c.begin(), c.end());
    offsets.push_back(static_cast<int64_t>(connectivity.size()));
    types.push_back(Cells::kVtkCell);
  }
  for (const auto& f : facets) {
    connectivity.insert(connectivity.end(), f.begin(), f.end());
    offsets.push_back(static_cast<int64_t>(connectivity.size()));
    types.push_back(Cells::kVtkFacet);
  }
  write_data_array(b, "connectivity", connectivity);
  write_data_array(b, "offsets", offsets);
  write_data_array(b, "types", types);
  b.text("      </Cells>\n");

  b.text("      <CellData Scalars=\"quality\">\n");
  std::vector<double> quality(num_cells, nan), angle(num_cells, nan);
  for (size_t i = 0; i < num_interior; ++i) {
    quality[i] = Cells::quality(mesh, cells[i]);
    angle[i] = Cells::angle(mesh, cells[i]);
  }
  write_data_array(b, "quality", quality);
  write_data_array(b, Cells::kAngleName, angle);
  std::vector<int32_t> physical(num_cells, kDomainPhysicalTag);
  for (size_t i = 0; i < num_facets; ++i) {
    physical[num_interior + i] = boundary_physical_tag(mesh.boundary_tags[i]);
  }
  write_data_array(b, "physical", physical);
  b.text("      </CellData>\n");

  b.text("    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n");
}

}  // namespace

void write_vtu(const Mesh& mesh, std::ostream& out) { write_vtu_cells(mesh, out); }

void write_vtu(const TetMesh& mesh, std::ostream& out) { write_vtu_cells(mesh, out); }

}  // namespace meshd
