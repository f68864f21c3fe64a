#include "client/npy_file.h"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <regex>

#include "core/common/error.h"

namespace meshd::cli {
namespace {

constexpr char kMagic[] = "\x93NUMPY";
constexpr size_t kMagicSize = 6;

struct Header {
  std::string descr;
  bool fortran = false;
  std::vector<int64_t> shape;
};

// The header is a Python dict literal, e.g. {'descr': '<f8', 'fortran_order': False,
// 'shape': (3, 4), }; numpy always writes these three keys.
template <class Fail>
Header parse_header(const std::string& text, const Fail& fail) {
  Header h;
  std::smatch m;
  if (!std::regex_search(text, m, std::regex(R"('descr'\s*:\s*'([^']*)')"))) fail("a .npy header without 'descr'");
  h.descr = m[1];
  if (!std::regex_search(text, m, std::regex(R"('fortran_order'\s*:\s*(True|False))")))
    fail("a .npy header without 'fortran_order'");
  h.fortran = m[1] == "True";
  if (!std::regex_search(text, m, std::regex(R"('shape'\s*:\s*\(([^)]*)\))"))) fail("a .npy header without 'shape'");
  const std::string dims = m[1];
  const std::regex number(R"(\d+)");
  for (std::sregex_iterator it(dims.begin(), dims.end(), number), end; it != end; ++it) {
    if (it->str().size() > 12) fail("a dimension larger than the file can hold");
    h.shape.push_back(std::stoll(it->str()));
  }
  return h;
}

}  // namespace

NpyArray read_npy(const std::string& path, const std::string& flag) {
  auto fail = [&](const std::string& why) { throw_invalid(flag, "'" + path + "': " + why); };
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(std::string("cannot open: ") + std::strerror(errno));
  const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (bytes.size() < kMagicSize + 4 || bytes.compare(0, kMagicSize, kMagic, kMagicSize) != 0)
    fail("not a NumPy .npy file (no \\x93NUMPY magic)");
  const auto major = static_cast<unsigned char>(bytes[6]);
  if (major < 1 || major > 3) fail("unknown .npy format version " + std::to_string(major));
  const size_t length_bytes = major == 1 ? 2 : 4;
  size_t header_length = 0;
  for (size_t k = 0; k < length_bytes && 8 + k < bytes.size(); ++k)
    header_length |= size_t(static_cast<unsigned char>(bytes[8 + k])) << (8 * k);
  const size_t data_start = 8 + length_bytes + header_length;
  if (data_start > bytes.size()) fail("the header runs past the end of the file");
  const Header h = parse_header(bytes.substr(8 + length_bytes, header_length), fail);

  size_t item = 0;
  if (h.descr == "<f4" || h.descr == "=f4") item = 4;
  if (h.descr == "<f8" || h.descr == "=f8") item = 8;
  if (item == 0)
    fail("values of type '" + h.descr + "'; allowed: float32 or float64, little-endian "
         "('<f4', '<f8'); convert with numpy's astype");
  size_t count = 1;
  for (const int64_t d : h.shape) {
    if (d != 0 && count > (bytes.size() / item) / static_cast<size_t>(d)) count = SIZE_MAX;
    else count *= static_cast<size_t>(d);
  }
  if (count == SIZE_MAX || bytes.size() - data_start != count * item)
    fail("holds " + std::to_string(bytes.size() - data_start) + " bytes of data where its shape "
         "needs " + (count == SIZE_MAX ? std::string("more") : std::to_string(count * item)));

  NpyArray out{h.shape, std::vector<float>(count)};
  const char* data = bytes.data() + data_start;
  auto value = [&](size_t k) -> float {
    if (item == 4) {
      float f;
      std::memcpy(&f, data + 4 * k, 4);
      return f;
    }
    double d;
    std::memcpy(&d, data + 8 * k, 8);
    return static_cast<float>(d);
  };
  if (!h.fortran || h.shape.size() < 2) {
    for (size_t k = 0; k < count; ++k) out.values[k] = value(k);
    return out;
  }
  // Fortran order: the first index runs fastest. Walk the C-order index and find its
  // Fortran-order position.
  std::vector<int64_t> index(h.shape.size(), 0);
  for (size_t k = 0; k < count; ++k) {
    size_t f = 0, stride = 1;
    for (size_t d = 0; d < h.shape.size(); ++d) {
      f += static_cast<size_t>(index[d]) * stride;
      stride *= static_cast<size_t>(h.shape[d]);
    }
    out.values[k] = value(f);
    for (size_t d = h.shape.size(); d-- > 0;) {
      if (++index[d] < h.shape[d]) break;
      index[d] = 0;
    }
  }
  return out;
}

NpyGrid read_npy_grid(const std::string& path, const std::string& flag, const std::string& what) {
  NpyArray a = read_npy(path, flag);
  const int64_t kMax = std::numeric_limits<uint32_t>::max();
  if (a.shape.size() != 2 || a.shape[0] < 2 || a.shape[1] < 2 || a.shape[0] > kMax ||
      a.shape[1] > kMax) {
    std::string shape;
    for (const int64_t d : a.shape) shape += (shape.empty() ? "" : ", ") + std::to_string(d);
    throw_invalid(flag, "'" + path + "': an array of shape (" + shape + "); " + what +
                            " is 2-D, indexed [row j, column i], at least 2 x 2");
  }
  return {static_cast<uint32_t>(a.shape[1]), static_cast<uint32_t>(a.shape[0]),
          std::move(a.values)};
}

}  // namespace meshd::cli
