// A small output buffer for the file writers: numbers go through std::to_chars into one block
// that is handed to the stream a megabyte at a time. iostream's formatted output is several
// times slower, which shows at a million triangles. Doubles are written in the shortest form
// that reads back to the same value, so text files lose nothing.
#pragma once

#include <charconv>
#include <cstdint>
#include <cstring>
#include <ostream>
#include <string_view>
#include <type_traits>
#include <vector>

namespace meshd {

class TextBuffer {
 public:
  explicit TextBuffer(std::ostream& out) : out_(out) { buffer_.reserve(kFlushBytes + kSlack); }
  TextBuffer(const TextBuffer&) = delete;
  TextBuffer& operator=(const TextBuffer&) = delete;
  ~TextBuffer() { flush(); }

  TextBuffer& text(std::string_view s) {
    buffer_.insert(buffer_.end(), s.begin(), s.end());
    return maybe_flush();
  }
  TextBuffer& character(char c) {
    buffer_.push_back(c);
    return maybe_flush();
  }
  // Integers in decimal, doubles in shortest round-trip form ("0.1", "1e-07", "2").
  template <typename T>
  requires std::is_arithmetic_v<T> TextBuffer& number(T value) {
    char s[32];
    const auto result = std::to_chars(s, s + sizeof(s), value);
    buffer_.insert(buffer_.end(), s, result.ptr);
    return maybe_flush();
  }
  // The object representation of value, in the machine's byte order (binary MSH asks for that).
  template <typename T>
  requires std::is_trivially_copyable_v<T> TextBuffer& raw(const T& value) {
    const size_t at = buffer_.size();
    buffer_.resize(at + sizeof(T));
    std::memcpy(buffer_.data() + at, &value, sizeof(T));
    return maybe_flush();
  }

  void flush() {
    if (!buffer_.empty()) out_.write(buffer_.data(), static_cast<std::streamsize>(buffer_.size()));
    buffer_.clear();
  }

 private:
  static constexpr size_t kFlushBytes = size_t{1} << 20;
  static constexpr size_t kSlack = 256;

  TextBuffer& maybe_flush() {
    if (buffer_.size() >= kFlushBytes) flush();
    return *this;
  }

  std::ostream& out_;
  std::vector<char> buffer_;
};

}  // namespace meshd
