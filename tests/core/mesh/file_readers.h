// Small readers of the writers' output, independent of the writers, shared by the tests of both
// kinds of mesh: MSH sections, binary MSH values, and VTU's base64 DataArrays.
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace meshd::testing {

// ---- MSH ---------------------------------------------------------------------------------------

// The text between "$Name\n" and "$EndName\n", or "<missing>".
inline std::string section(const std::string& file, const std::string& name) {
  const std::string begin = "$" + name + "\n", end = "$End" + name + "\n";
  const size_t a = file.find(begin);
  const size_t b = file.find(end, a);
  if (a == std::string::npos || b == std::string::npos) return "<missing>";
  return file.substr(a + begin.size(), b - a - begin.size());
}

// Reads the binary values of a MSH 4.1 file written with data-size 8 on this machine.
class BinaryReader {
 public:
  BinaryReader(const std::string& file, size_t at) : file_(file), at_(at) {}
  template <typename T>
  T get() {
    T v{};
    EXPECT_LE(at_ + sizeof(T), file_.size());
    if (at_ + sizeof(T) <= file_.size()) std::memcpy(&v, file_.data() + at_, sizeof(T));
    at_ += sizeof(T);
    return v;
  }
  uint64_t size() { return get<uint64_t>(); }
  int32_t integer() { return get<int32_t>(); }
  double real() { return get<double>(); }
  // Expects text (such as "\n$EndNodes\n") at the current position and skips it.
  bool expect(const std::string& text) {
    const bool ok = file_.compare(at_, text.size(), text) == 0;
    at_ += text.size();
    return ok;
  }
  size_t position() const { return at_; }

 private:
  const std::string& file_;
  size_t at_;
};

// ---- VTU ---------------------------------------------------------------------------------------

// An independent RFC 4648 decoder; returns false on any character outside the alphabet, a
// length that is not a multiple of 4, or misplaced padding.
inline bool base64_decode(const std::string& text, std::vector<uint8_t>& bytes) {
  static const std::string kAlphabet =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  if (text.size() % 4 != 0) return false;
  bytes.clear();
  for (size_t i = 0; i < text.size(); i += 4) {
    uint32_t quad = 0;
    int padding = 0;
    for (int k = 0; k < 4; ++k) {
      const char c = text[i + k];
      if (c == '=') {
        if (i + 4 != text.size() || k < 2) return false;
        ++padding;
        quad <<= 6;
        continue;
      }
      if (padding > 0) return false;
      const size_t v = kAlphabet.find(c);
      if (v == std::string::npos) return false;
      quad = (quad << 6) | static_cast<uint32_t>(v);
    }
    bytes.push_back(static_cast<uint8_t>(quad >> 16));
    if (padding < 2) bytes.push_back(static_cast<uint8_t>(quad >> 8));
    if (padding < 1) bytes.push_back(static_cast<uint8_t>(quad));
  }
  return true;
}

// The base64 text of the DataArray named name (the first one), or "" when absent.
inline std::string array_text(const std::string& file, const std::string& name) {
  const size_t tag = file.find("Name=\"" + name + "\"");
  if (tag == std::string::npos) return "";
  const size_t begin = file.find('>', tag) + 1;
  const size_t end = file.find("</DataArray>", begin);
  std::string text = file.substr(begin, end - begin);
  std::erase_if(text, [](char c) { return c == ' ' || c == '\n'; });
  return text;
}

// Decodes a binary DataArray: checks the UInt64 byte-count header and returns the values.
template <typename T>
std::vector<T> decode(const std::string& file, const std::string& name) {
  std::vector<uint8_t> bytes;
  EXPECT_TRUE(base64_decode(array_text(file, name), bytes)) << name;
  if (bytes.size() < 8) {
    ADD_FAILURE() << name << ": no header";
    return {};
  }
  uint64_t count;
  std::memcpy(&count, bytes.data(), 8);
  EXPECT_EQ(count, bytes.size() - 8) << name << ": header disagrees with the data";
  EXPECT_EQ(count % sizeof(T), 0u) << name;
  std::vector<T> values(count / sizeof(T));
  std::memcpy(values.data(), bytes.data() + 8, values.size() * sizeof(T));
  return values;
}

}  // namespace meshd::testing
