// SPDX-License-Identifier: MIT
#pragma once
#include <charconv>
#include <cstring>
#include <ostream>
#include <string>
#include <string_view>
#include <type_traits>

namespace meshmorph::detail {

/// Buffered output with std::to_chars number formatting (shortest exact doubles, no locale).
class OutBuffer {
 public:
  explicit OutBuffer(std::ostream& out) : out_(out) { buf_.reserve(k_flush + 4096); }
  ~OutBuffer() { flush(); }
  OutBuffer(const OutBuffer&) = delete;
  OutBuffer& operator=(const OutBuffer&) = delete;

  OutBuffer& operator<<(std::string_view s) {
    buf_.append(s);
    maybe_flush();
    return *this;
  }
  OutBuffer& operator<<(char ch) {
    buf_.push_back(ch);
    return *this;
  }
  template <class T>
    requires std::is_arithmetic_v<T>
  OutBuffer& operator<<(T v) {
    char tmp[64];
    const auto r = std::to_chars(tmp, tmp + sizeof(tmp), v);
    buf_.append(tmp, r.ptr);
    maybe_flush();
    return *this;
  }
  /// Appends the raw bytes of `v` (little-endian host).
  template <class T>
  void raw(const T& v) {
    char tmp[sizeof(T)];
    std::memcpy(tmp, &v, sizeof(T));
    buf_.append(tmp, sizeof(T));
    maybe_flush();
  }
  void flush() {
    if (!buf_.empty()) out_.write(buf_.data(), static_cast<std::streamsize>(buf_.size()));
    buf_.clear();
  }

 private:
  static constexpr std::size_t k_flush = 1 << 20;
  void maybe_flush() {
    if (buf_.size() >= k_flush) flush();
  }
  std::ostream& out_;
  std::string buf_;
};

}  // namespace meshmorph::detail
