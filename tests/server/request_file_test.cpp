#include "client/request_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "core/common/error.h"

namespace meshd {
namespace {

// The error that `fn` throws, after checking that it is INVALID_ARGUMENT on "request".
template <typename Fn>
std::string failure(Fn fn) {
  try {
    fn();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::kInvalidArgument);
    EXPECT_EQ(e.field(), "request");
    return e.detail();
  }
  ADD_FAILURE() << "no error";
  return "";
}

class RequestFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("meshd_request_file_test_" +
            std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::string write(const std::string& name, const std::string& text) {
    const std::string path = (dir_ / name).string();
    std::ofstream(path) << text;
    return path;
  }

  std::filesystem::path dir_;
};

TEST_F(RequestFile, ReadsTextFormat) {
  const std::string path = write("disk.textproto",
                                 "# a comment\n"
                                 "geometry { name: \"outer\" circle { radius: 1 } }\n"
                                 "h0: 0.04\n");
  const v1::MeshRequest request = read_request_file(path);
  EXPECT_EQ(request.geometry().name(), "outer");
  EXPECT_EQ(request.geometry().circle().radius(), 1.0);
  EXPECT_EQ(request.h0(), 0.04);
}

TEST_F(RequestFile, EmptyFileIsAnEmptyRequest) {
  EXPECT_FALSE(read_request_file(write("empty.textproto", "")).has_geometry());
}

TEST_F(RequestFile, MissingFile) {
  const std::string path = (dir_ / "nope.textproto").string();
  const std::string message = failure([&] { read_request_file(path); });
  EXPECT_NE(message.find("cannot open '" + path + "': No such file or directory"),
            std::string::npos)
      << message;
}

TEST_F(RequestFile, Directory) {
  const std::string message = failure([&] { read_request_file(dir_.string()); });
  EXPECT_NE(message.find("is a directory"), std::string::npos) << message;
}

TEST_F(RequestFile, SyntaxErrorGivesLineAndColumn) {
  const std::string path = write("bad.textproto",
                                 "geometry {\n"
                                 "  circle { radius: = 1 }\n"
                                 "}\n");
  const std::string message = failure([&] { read_request_file(path); });
  // Line 2, column 20 (the '='), both counted from 1; the parser's own words follow.
  EXPECT_EQ(message.rfind(path + ":2:20: ", 0), 0u) << message;
}

TEST_F(RequestFile, UnknownFieldGivesLineAndColumn) {
  const std::string message =
      failure([] { parse_request_text("h0: 0.1\ngeometry { circel { radius: 1 } }\n", "x.txt"); });
  EXPECT_EQ(message.rfind("x.txt:2:", 0), 0u) << message;
  EXPECT_NE(message.find("circel"), std::string::npos) << message;
}

}  // namespace
}  // namespace meshd
