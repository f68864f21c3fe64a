// read_npy: the layouts numpy writes (format versions 1 and 2, float32 and float64, C and Fortran
// order) come back in C order, and every file it cannot take is an error naming the flag.
#include "client/npy_file.h"

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <unistd.h>
#include <string>
#include <vector>

#include "core/common/error.h"

namespace meshd::cli {
namespace {

// A .npy file as numpy writes it: magic, version, header length, the dict padded with spaces to
// a multiple of 64 bytes and ended by a newline, then the raw values.
template <class T>
std::string npy_bytes(int version, const std::string& descr, bool fortran,
                      const std::string& shape, const std::vector<T>& values) {
  std::string dict = "{'descr': '" + descr + "', 'fortran_order': " +
                     (fortran ? "True" : "False") + ", 'shape': " + shape + ", }";
  const size_t fixed = 6 + 2 + (version == 1 ? 2 : 4);
  while ((fixed + dict.size() + 1) % 64 != 0) dict += ' ';
  dict += '\n';
  std::string out = "\x93NUMPY";
  out += static_cast<char>(version);
  out += '\0';
  for (size_t k = 0; k < (version == 1 ? 2u : 4u); ++k)
    out += static_cast<char>((dict.size() >> (8 * k)) & 0xff);
  out += dict;
  out.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
  return out;
}

class NpyFile : public ::testing::Test {
 protected:
  std::string write(const std::string& bytes) {
    std::ofstream(path_, std::ios::binary) << bytes;
    return path_;
  }
  void TearDown() override { std::filesystem::remove(path_); }

 private:
  std::string path_ = (std::filesystem::temp_directory_path() /
                       ("npy_file_test_" + std::to_string(::getpid()) + ".npy"))
                          .string();
};

std::string error_of(const std::string& path) {
  try {
    read_npy(path, "--size-grid");
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::kInvalidArgument);
    EXPECT_EQ(e.field(), "--size-grid");
    return e.detail();
  }
  ADD_FAILURE() << "no error";
  return "";
}

TEST_F(NpyFile, Float64InCOrder) {
  const std::vector<double> v{0.5, 1.5, 2.5, 3.5, 4.5, 5.5};
  const NpyArray a = read_npy(write(npy_bytes(1, "<f8", false, "(2, 3)", v)), "--size-grid");
  EXPECT_EQ(a.shape, (std::vector<int64_t>{2, 3}));
  EXPECT_EQ(a.values, (std::vector<float>{0.5f, 1.5f, 2.5f, 3.5f, 4.5f, 5.5f}));
}

TEST_F(NpyFile, Float32InFortranOrderComesBackInCOrder) {
  // The array [[1, 2, 3], [4, 5, 6]] stored column by column.
  const std::vector<float> v{1, 4, 2, 5, 3, 6};
  const NpyArray a = read_npy(write(npy_bytes(2, "<f4", true, "(2, 3)", v)), "--size-grid");
  EXPECT_EQ(a.shape, (std::vector<int64_t>{2, 3}));
  EXPECT_EQ(a.values, (std::vector<float>{1, 2, 3, 4, 5, 6}));
}

TEST_F(NpyFile, OneDimensionalAndEmptyArrays) {
  const NpyArray a = read_npy(write(npy_bytes(1, "<f4", false, "(3,)", std::vector<float>{7, 8, 9})),
                              "--size-grid");
  EXPECT_EQ(a.shape, (std::vector<int64_t>{3}));
  EXPECT_EQ(a.values.size(), 3u);
  const NpyArray e = read_npy(write(npy_bytes(1, "<f8", false, "(0, 4)", std::vector<double>{})),
                              "--size-grid");
  EXPECT_EQ(e.shape, (std::vector<int64_t>{0, 4}));
  EXPECT_TRUE(e.values.empty());
}

TEST_F(NpyFile, FilesItCannotTakeAreErrorsThatSayWhy) {
  EXPECT_NE(error_of(write("P5\n3 2\n255\n")).find("not a NumPy .npy file"), std::string::npos);
  const std::vector<int64_t> ints{1, 2, 3, 4};
  EXPECT_NE(error_of(write(npy_bytes(1, "<i8", false, "(2, 2)", ints))).find("'<i8'"),
            std::string::npos);
  EXPECT_NE(error_of(write(npy_bytes(1, ">f8", false, "(2, 2)", ints))).find("little-endian"),
            std::string::npos);
  std::string truncated = npy_bytes(1, "<f8", false, "(2, 3)", std::vector<double>(6, 1.0));
  truncated.resize(truncated.size() - 8);
  EXPECT_NE(error_of(write(truncated)).find("bytes of data"), std::string::npos);
  EXPECT_NE(error_of(write(npy_bytes(1, "<f8", false, "(99999999999, 99999999999)",
                                     std::vector<double>(4, 1.0))))
                .find("bytes of data"),
            std::string::npos);
  EXPECT_NE(error_of("/nonexistent/grid.npy").find("cannot open"), std::string::npos);
}

}  // namespace
}  // namespace meshd::cli
