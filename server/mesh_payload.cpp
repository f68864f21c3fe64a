#include "server/mesh_payload.h"

#include <google/protobuf/wire_format_lite.h>

#include <algorithm>
#include <cstdint>
#include <functional>
#include <vector>

#include "meshd/v1/mesh.pb.h"

namespace meshd {

namespace {

using google::protobuf::internal::WireFormatLite;

// Values a piece: a piece is sized and written by one thread.
constexpr size_t kPieceValues = size_t{1} << 15;

// The fields in field-number order, as protobuf serializes them: packed repeated scalars
// (proto3's encoding), each string with its own tag, scalars only when not zero. Each field is
// sized when added and written by take(), into a payload allocated once: growing it field by
// field copied it and touched fresh memory for each copy.
class PayloadWriter {
 public:
  explicit PayloadWriter(ThreadPool* pool) : pool_(pool) {}

  // A packed double field of `n` values, value(i) the i-th.
  template <typename Value>
  void doubles(int field, size_t n, Value value) {
    if (n == 0) return;
    add(field, 8 * n, [this, n, value](uint8_t* out) {
      for_chunks(pool_, n, kPieceValues, [&](size_t, size_t begin, size_t end) {
        uint8_t* target = out + 8 * begin;
        for (size_t i = begin; i < end; ++i)
          target = WireFormatLite::WriteDoubleNoTagToArray(value(i), target);
      });
    });
  }

  // A packed int32 field: each piece's size now, each piece at its offset in take().
  void int32s(int field, const int32_t* values, size_t n) {
    if (n == 0) return;
    std::vector<size_t> offsets(ThreadPool::chunk_count(n, kPieceValues) + 1, 0);
    for_chunks(pool_, n, kPieceValues, [&](size_t piece, size_t begin, size_t end) {
      size_t bytes = 0;
      for (size_t i = begin; i < end; ++i) bytes += WireFormatLite::Int32Size(values[i]);
      offsets[piece + 1] = bytes;
    });
    for (size_t p = 1; p < offsets.size(); ++p) offsets[p] += offsets[p - 1];
    const size_t length = offsets.back();
    add(field, length, [this, values, n, offsets = std::move(offsets)](uint8_t* out) {
      for_chunks(pool_, n, kPieceValues, [&](size_t piece, size_t begin, size_t end) {
        uint8_t* target = out + offsets[piece];
        for (size_t i = begin; i < end; ++i)
          target = WireFormatLite::WriteInt32NoTagToArray(values[i], target);
      });
    });
  }

  void strings(int field, const std::vector<std::string>& values) {
    for (const std::string& s : values)
      add(field, s.size(), [&s](uint8_t* out) { std::copy(s.begin(), s.end(), out); });
  }

  void uint32(int field, uint32_t value) {
    if (value == 0) return;
    uint8_t bytes[2 * 5];
    uint8_t* end = WireFormatLite::WriteUInt32ToArray(field, value, bytes);
    fields_.push_back(
        {std::string(reinterpret_cast<const char*>(bytes), reinterpret_cast<const char*>(end)), 0,
         nullptr});
  }

  std::string take() {
    size_t total = 0;
    for (const Field& f : fields_) total += f.header.size() + f.length;
    std::string payload(total, '\0');
    auto* out = reinterpret_cast<uint8_t*>(payload.data());
    for (const Field& f : fields_) {
      out = std::copy(f.header.begin(), f.header.end(), out);
      if (f.write) f.write(out);
      out += f.length;
    }
    fields_.clear();
    return payload;
  }

 private:
  struct Field {
    std::string header;  // the tag, and the length of a length-delimited field
    size_t length;       // the bytes that `write` puts after it
    std::function<void(uint8_t*)> write;
  };

  // A length-delimited field of `length` bytes that `write` fills.
  void add(int field, size_t length, std::function<void(uint8_t*)> write) {
    uint8_t bytes[2 * 10];
    uint8_t* end =
        WireFormatLite::WriteTagToArray(field, WireFormatLite::WIRETYPE_LENGTH_DELIMITED, bytes);
    end = WireFormatLite::WriteUInt64NoTagToArray(length, end);
    fields_.push_back(
        {std::string(reinterpret_cast<const char*>(bytes), reinterpret_cast<const char*>(end)),
         length, std::move(write)});
  }

  ThreadPool* pool_;
  std::vector<Field> fields_;
};

// The flat indices of an array of index tuples.
template <size_t K>
const int32_t* flat(const std::vector<std::array<int32_t, K>>& tuples) {
  static_assert(sizeof(std::array<int32_t, K>) == K * sizeof(int32_t));
  return tuples.empty() ? nullptr : tuples.front().data();
}

}  // namespace

std::string mesh_payload(const Mesh& mesh, ThreadPool* pool) {
  PayloadWriter w(pool);
  const auto& p = mesh.points;
  w.doubles(v1::MeshData::kPointsFieldNumber, 2 * p.size(),
            [&](size_t i) { return i % 2 == 0 ? p[i / 2].x : p[i / 2].y; });
  w.int32s(v1::MeshData::kTrianglesFieldNumber, flat(mesh.triangles), 3 * mesh.triangles.size());
  w.int32s(v1::MeshData::kBoundaryEdgesFieldNumber, flat(mesh.boundary_edges),
           2 * mesh.boundary_edges.size());
  w.int32s(v1::MeshData::kBoundaryTagsFieldNumber, mesh.boundary_tags.data(),
           mesh.boundary_tags.size());
  w.strings(v1::MeshData::kBoundaryNamesFieldNumber, mesh.boundary_names);
  return w.take();
}

std::string mesh_payload(const TetMesh& mesh, ThreadPool* pool) {
  PayloadWriter w(pool);
  const auto& p = mesh.points;
  w.doubles(v1::MeshData::kPointsFieldNumber, 3 * p.size(), [&](size_t i) {
    const Vec3& q = p[i / 3];
    return i % 3 == 0 ? q.x : i % 3 == 1 ? q.y : q.z;
  });
  w.int32s(v1::MeshData::kBoundaryTagsFieldNumber, mesh.boundary_tags.data(),
           mesh.boundary_tags.size());
  w.strings(v1::MeshData::kBoundaryNamesFieldNumber, mesh.boundary_names);
  w.uint32(v1::MeshData::kDimensionFieldNumber, 3);
  w.int32s(v1::MeshData::kTetrahedraFieldNumber, flat(mesh.tets), 4 * mesh.tets.size());
  w.int32s(v1::MeshData::kBoundaryFacesFieldNumber, flat(mesh.boundary_faces),
           3 * mesh.boundary_faces.size());
  return w.take();
}

}  // namespace meshd
