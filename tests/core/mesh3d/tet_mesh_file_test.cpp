// write_mesh and write_mesh_file for tetrahedra: the format switch for tetrahedra, and the file
// written through a temporary as for triangles.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "core/common/error.h"
#include "core/mesh/mesh_file.h"
#include "core/mesh/msh22_writer.h"
#include "core/mesh/msh41_writer.h"
#include "core/mesh/vtu_writer.h"
#include "tests/core/mesh3d/structured_tet_mesh.h"

namespace meshd {
namespace {

namespace fs = std::filesystem;

constexpr MeshFormat kTetFormats[] = {MeshFormat::kMsh41, MeshFormat::kMsh41Binary,
                                      MeshFormat::kMsh22, MeshFormat::kVtu};

std::string written(const TetMesh& mesh, MeshFormat format) {
  std::ostringstream out(std::ios::binary);
  write_mesh(mesh, out, format);
  return out.str();
}

TEST(WriteTetMesh, EachFormatGoesToItsWriter) {
  const TetMesh mesh = testing::structured_cube_mesh(1);
  std::ostringstream msh41, binary, msh22, vtu;
  write_msh41(mesh, msh41, MshEncoding::kAscii);
  write_msh41(mesh, binary, MshEncoding::kBinary);
  write_msh22(mesh, msh22);
  write_vtu(mesh, vtu);
  EXPECT_EQ(written(mesh, MeshFormat::kMsh41), msh41.str());
  EXPECT_EQ(written(mesh, MeshFormat::kMsh41Binary), binary.str());
  EXPECT_EQ(written(mesh, MeshFormat::kMsh22), msh22.str());
  EXPECT_EQ(written(mesh, MeshFormat::kVtu), vtu.str());
  for (const MeshFormat f : kTetFormats) {
    std::ostringstream generic(std::ios::binary);
    write_mesh(mesh, generic, f);  // the name templates over both kinds of mesh call
    EXPECT_EQ(generic.str(), written(mesh, f)) << format_name(f);
  }
}

// The picture: the faces that face the viewer (of a cube seen from a corner, half of them), one
// path each, and the legend's sizes.
TEST(WriteTetMesh, SvgShowsTheFacesTowardsTheViewer) {
  const TetMesh mesh = testing::structured_cube_mesh(2);
  std::ostringstream out;
  write_mesh(mesh, out, MeshFormat::kSvg);
  const std::string svg = out.str();
  EXPECT_EQ(svg.rfind("<svg", 0), 0u);
  EXPECT_NE(svg.find("</svg>"), std::string::npos);
  size_t paths = 0;
  for (size_t at = svg.find("<path"); at != std::string::npos; at = svg.find("<path", at + 1))
    ++paths;
  EXPECT_EQ(paths, mesh.boundary_faces.size() / 2);
  EXPECT_NE(svg.find(std::to_string(mesh.tets.size()) + " tetrahedra"), std::string::npos);
}

class WriteTetMeshFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("meshd_tet_mesh_file_test_" +
            std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  size_t files_in_dir() const {
    return static_cast<size_t>(std::distance(fs::directory_iterator(dir_), {}));
  }

  static std::string read_file(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
  }

  fs::path dir_;
};

TEST_F(WriteTetMeshFileTest, WritesWhatTheStreamWriterWritesAndLeavesNoTemporary) {
  const TetMesh mesh = testing::structured_cube_mesh(2);
  for (const MeshFormat f : kTetFormats) {
    const fs::path path = dir_ / (std::string("cube_") + format_name(f));
    write_mesh_file(mesh, path.string(), f);
    EXPECT_EQ(read_file(path), written(mesh, f)) << format_name(f);
  }
  EXPECT_EQ(files_in_dir(), 4u);
}

TEST_F(WriteTetMeshFileTest, SvgIsWrittenThroughATemporaryToo) {
  const fs::path path = dir_ / "cube.svg";
  std::ofstream(path) << "old";
  write_mesh_file(testing::structured_cube_mesh(1), path.string(), MeshFormat::kSvg);
  EXPECT_EQ(read_file(path).rfind("<svg", 0), 0u);
  EXPECT_EQ(files_in_dir(), 1u);
}

TEST_F(WriteTetMeshFileTest, AWriterErrorKeepsTheOldFile) {
  const fs::path path = dir_ / "cube.msh";
  std::ofstream(path) << "old";
  TetMesh mesh = testing::structured_cube_mesh(1);
  mesh.boundary_tags.pop_back();
  try {
    write_mesh_file(mesh, path.string(), MeshFormat::kMsh41);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::kInternal);
    EXPECT_EQ(e.field(), "mesh");
  }
  EXPECT_EQ(read_file(path), "old");
  EXPECT_EQ(files_in_dir(), 1u);
}

TEST_F(WriteTetMeshFileTest, AMissingDirectoryIsAClearError) {
  try {
    write_mesh_file(testing::structured_cube_mesh(1), (dir_ / "nope" / "cube.vtu").string(),
                    MeshFormat::kVtu);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::kInvalidArgument);
    EXPECT_EQ(e.field(), "output");
  }
}

}  // namespace
}  // namespace meshd
