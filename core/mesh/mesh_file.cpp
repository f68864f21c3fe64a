#include "core/mesh/mesh_file.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <type_traits>

#include "core/common/error.h"
#include "core/mesh/msh22_writer.h"
#include "core/mesh/msh41_writer.h"
#include "core/mesh/svg_writer.h"
#include "core/mesh/vtu_writer.h"
#include "core/mesh3d/svg_surface3d.h"

namespace meshd {
namespace {

struct FormatEntry {
  MeshFormat format;
  const char* name;
  const char* extension;  // empty when the format has none of its own
};

constexpr FormatEntry kFormats[] = {
    {MeshFormat::kMsh41, "msh41", ".msh"},   {MeshFormat::kMsh41Binary, "msh41-binary", ""},
    {MeshFormat::kMsh22, "msh22", ".msh22"}, {MeshFormat::kVtu, "vtu", ".vtu"},
    {MeshFormat::kSvg, "svg", ".svg"},
};

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

std::string system_error_text() { return errno != 0 ? std::strerror(errno) : "unknown error"; }

// A name beside the target that no other writer picks: same directory, so rename is atomic.
std::string temporary_path(const std::string& path) {
  std::random_device random;
  const uint64_t id = (uint64_t{random()} << 32) ^ random();
  char suffix[32];
  std::snprintf(suffix, sizeof(suffix), ".tmp-%016llx", static_cast<unsigned long long>(id));
  return path + suffix;
}

}  // namespace

const char* format_name(MeshFormat format) {
  for (const auto& entry : kFormats) {
    if (entry.format == format) return entry.name;
  }
  return "unknown";
}

MeshFormat format_from_path(const std::string& path, const std::string& field) {
  const std::string extension = lower(std::filesystem::path(path).extension().string());
  for (const auto& entry : kFormats) {
    if (*entry.extension != '\0' && extension == entry.extension) return entry.format;
  }
  throw_invalid(field, "cannot tell the mesh format of \"" + path +
                           "\" from its extension; allowed: .msh (MSH 4.1), .msh22 (MSH 2.2), "
                           ".vtu (VTK XML), .svg (picture)");
}

MeshFormat parse_format_name(const std::string& name, const std::string& field) {
  for (const auto& entry : kFormats) {
    if (name == entry.name) return entry.format;
  }
  throw_invalid(
      field, "unknown mesh format \"" + name + "\"; allowed: msh41, msh41-binary, msh22, vtu, svg");
}

namespace {

template <typename M>
void write_any_mesh(const M& mesh, std::ostream& out, MeshFormat format) {
  switch (format) {
    case MeshFormat::kMsh41:
      return write_msh41(mesh, out, MshEncoding::kAscii);
    case MeshFormat::kMsh41Binary:
      return write_msh41(mesh, out, MshEncoding::kBinary);
    case MeshFormat::kMsh22:
      return write_msh22(mesh, out);
    case MeshFormat::kVtu:
      return write_vtu(mesh, out);
    case MeshFormat::kSvg:
      if constexpr (std::is_same_v<M, Mesh>) {
        return write_svg(mesh, out);
      } else {
        return write_svg_surface3d(mesh, out);
      }
  }
  throw Error(ErrorCode::kInternal, "", "write_mesh: unknown MeshFormat value");
}

}  // namespace

void write_mesh(const Mesh& mesh, std::ostream& out, MeshFormat format) {
  write_any_mesh(mesh, out, format);
}

void write_mesh(const TetMesh& mesh, std::ostream& out, MeshFormat format) {
  write_any_mesh(mesh, out, format);
}

namespace {

// write_mesh_file for either kind of mesh.
template <typename M>
void write_file(const M& mesh, const std::string& path, MeshFormat format) {
  const std::string temporary = temporary_path(path);
  // Removes the temporary file on every exit but the successful rename.
  struct Cleanup {
    const std::string& path;
    bool armed = true;
    ~Cleanup() {
      std::error_code ignored;
      if (armed) std::filesystem::remove(path, ignored);
    }
  } cleanup{temporary};

  errno = 0;
  std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
  if (!out) {
    cleanup.armed = false;  // nothing was created
    throw_invalid("output", "cannot create \"" + temporary + "\": " + system_error_text());
  }
  write_mesh(mesh, out, format);
  errno = 0;
  out.flush();
  out.close();
  if (!out) {
    throw Error(ErrorCode::kResourceExhausted, "output",
                "writing \"" + temporary + "\" failed: " + system_error_text());
  }
  std::error_code error;
  std::filesystem::rename(temporary, path, error);
  if (error) {
    throw_invalid("output",
                  "cannot rename \"" + temporary + "\" to \"" + path + "\": " + error.message());
  }
  cleanup.armed = false;
}

}  // namespace

void write_mesh_file(const Mesh& mesh, const std::string& path, MeshFormat format) {
  write_file(mesh, path, format);
}

void write_mesh_file(const TetMesh& mesh, const std::string& path, MeshFormat format) {
  write_file(mesh, path, format);
}

}  // namespace meshd
