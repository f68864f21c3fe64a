#include "core/mesh/mesh_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "core/common/error.h"
#include "tests/core/mesh/structured_mesh.h"

namespace meshd {
namespace {

namespace fs = std::filesystem;

TEST(FormatFromPath, KnownExtensions) {
  EXPECT_EQ(format_from_path("a/b/mesh.msh"), MeshFormat::kMsh41);
  EXPECT_EQ(format_from_path("mesh.MSH"), MeshFormat::kMsh41);
  EXPECT_EQ(format_from_path("mesh.msh22"), MeshFormat::kMsh22);
  EXPECT_EQ(format_from_path("mesh.vtu"), MeshFormat::kVtu);
  EXPECT_EQ(format_from_path("dir.v2/mesh.svg"), MeshFormat::kSvg);
}

TEST(FormatFromPath, UnknownExtensionNamesTheFieldAndTheAllowedOnes) {
  for (const std::string path : {"mesh.stl", "mesh", "mesh.msh.bak", "msh"}) {
    try {
      format_from_path(path);
      ADD_FAILURE() << path;
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), ErrorCode::kInvalidArgument);
      EXPECT_EQ(e.field(), "output");
      for (const char* allowed : {".msh", ".msh22", ".vtu", ".svg"}) {
        EXPECT_NE(e.detail().find(allowed), std::string::npos) << e.detail();
      }
    }
  }
  try {
    format_from_path("x.obj", "options.output_path");
  } catch (const Error& e) {
    EXPECT_EQ(e.field(), "options.output_path");
  }
}

TEST(ParseFormatName, AllNamesRoundTrip) {
  for (const MeshFormat f : {MeshFormat::kMsh41, MeshFormat::kMsh41Binary, MeshFormat::kMsh22,
                             MeshFormat::kVtu, MeshFormat::kSvg}) {
    EXPECT_EQ(parse_format_name(format_name(f)), f);
  }
  EXPECT_EQ(parse_format_name("msh41-binary"), MeshFormat::kMsh41Binary);
  try {
    parse_format_name("MSH");
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::kInvalidArgument);
    EXPECT_EQ(e.field(), "format");
    EXPECT_NE(e.detail().find("msh41-binary"), std::string::npos);
  }
}

class WriteMeshFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("meshd_mesh_file_test_" +
            std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  size_t files_in_dir() const {
    return static_cast<size_t>(std::distance(fs::directory_iterator(dir_), {}));
  }

  fs::path dir_;
};

std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST_F(WriteMeshFileTest, WritesWhatTheStreamWriterWritesAndLeavesNoTemporary) {
  const Mesh mesh = testing::structured_square_mesh(3, 3);
  for (const MeshFormat f : {MeshFormat::kMsh41, MeshFormat::kMsh41Binary, MeshFormat::kMsh22,
                             MeshFormat::kVtu, MeshFormat::kSvg}) {
    const fs::path path = dir_ / (std::string("mesh_") + format_name(f));
    write_mesh_file(mesh, path.string(), f);
    std::ostringstream expected(std::ios::binary);
    write_mesh(mesh, expected, f);
    EXPECT_EQ(read_file(path), expected.str()) << format_name(f);
  }
  EXPECT_EQ(files_in_dir(), 5u);
}

TEST_F(WriteMeshFileTest, ReplacesAnExistingFile) {
  const fs::path path = dir_ / "mesh.msh";
  std::ofstream(path) << "old";
  write_mesh_file(testing::structured_square_mesh(1, 1), path.string(), MeshFormat::kMsh41);
  EXPECT_EQ(read_file(path).rfind("$MeshFormat\n", 0), 0u);
  EXPECT_EQ(files_in_dir(), 1u);
}

TEST_F(WriteMeshFileTest, MissingDirectoryIsAClearError) {
  const std::string path = (dir_ / "no_such_dir" / "mesh.msh").string();
  try {
    write_mesh_file(testing::structured_square_mesh(1, 1), path, MeshFormat::kMsh41);
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::kInvalidArgument);
    EXPECT_EQ(e.field(), "output");
    EXPECT_NE(e.detail().find("no_such_dir"), std::string::npos) << e.detail();
    EXPECT_NE(e.detail().find("No such file or directory"), std::string::npos) << e.detail();
  }
}

TEST_F(WriteMeshFileTest, TargetThatIsADirectoryFailsAndCleansUp) {
  const fs::path path = dir_ / "taken.msh";
  fs::create_directory(path);
  EXPECT_THROW(
      write_mesh_file(testing::structured_square_mesh(1, 1), path.string(), MeshFormat::kMsh41),
      Error);
  EXPECT_EQ(files_in_dir(), 1u);  // only the directory itself
}

TEST_F(WriteMeshFileTest, WriterErrorRemovesTheTemporaryAndKeepsTheOldFile) {
  const fs::path path = dir_ / "mesh.vtu";
  std::ofstream(path) << "old";
  Mesh mesh = testing::structured_square_mesh(1, 1);
  mesh.boundary_tags[0] = 9;
  try {
    write_mesh_file(mesh, path.string(), MeshFormat::kVtu);
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::kInternal);
  }
  EXPECT_EQ(read_file(path), "old");
  EXPECT_EQ(files_in_dir(), 1u);
}

}  // namespace
}  // namespace meshd
