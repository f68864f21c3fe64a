// Reading a NumPy .npy file (format versions 1-3) as single-precision values: the way a gridded
// field (a size field, a signed-distance grid) comes from a user's own scripts.
//
// Accepted: little-endian or byte-order-free float32 and float64 ('<f4', '<f8'), C or Fortran
// order, any number of dimensions; values come back in C order (last index fastest). A grid
// array is indexed [row, column] = [j, i]: row j lies at y = origin.y + j * dy, counted upwards
// from the origin, not downwards as in an image.
// Every error is Error(kInvalidArgument) naming `flag` and the file.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace meshd::cli {

struct NpyArray {
  std::vector<int64_t> shape;
  std::vector<float> values;  // C order
};

NpyArray read_npy(const std::string& path, const std::string& flag);

// A grid: a 2-D array [rows j, columns i] of at least 2 x 2. `what` names it in the message of
// the error for any other shape ("a distance grid").
struct NpyGrid {
  uint32_t nx = 0, ny = 0;
  std::vector<float> values;  // ny rows of nx
};

NpyGrid read_npy_grid(const std::string& path, const std::string& flag, const std::string& what);

}  // namespace meshd::cli
