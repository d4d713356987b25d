// SPDX-License-Identifier: MIT
#pragma once
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>
#include <string_view>
#include <type_traits>

namespace meshmorph::detail {

/// Reads a whole file into memory; throws IoError when it cannot be opened or read.
std::string read_file(const std::filesystem::path& path);

/// 1-based line number of byte `offset` in `text`.
std::size_t line_of(std::string_view text, std::size_t offset);

/// "<file>: line N" or, for binary content, "<file>: byte offset N".
std::string location(const std::filesystem::path& file, std::string_view text, std::size_t offset, bool binary);

/// "<file>: line N: msg" (text content) or "<file>: byte offset N: msg" (binary content).
[[noreturn]] void throw_input_error(const std::filesystem::path& file, std::string_view text,
                                    std::size_t offset, bool binary, const std::string& msg);

/// A read position in a file held in memory, with tokenising and number parsing helpers
/// (std::from_chars, no locale). Errors name the file and the line, or the byte offset
/// while `binary` is set.
class Cursor {
 public:
  Cursor(std::filesystem::path file, std::string_view text) : file_(std::move(file)), text_(text) {}

  const std::filesystem::path& file() const { return file_; }
  std::string_view text() const { return text_; }
  std::size_t pos() const { return pos_; }
  void seek(std::size_t pos) { pos_ = pos; }
  bool binary = false;  ///< report byte offsets instead of lines

  [[noreturn]] void fail(const std::string& msg) const { fail_at(pos_, msg); }
  /// "<file>: line N" or "<file>: byte offset N" for `offset`.
  std::string where(std::size_t offset) const;
  [[noreturn]] void fail_at(std::size_t offset, const std::string& msg) const {
    throw_input_error(file_, text_, offset, binary, msg);
  }

  /// Skips spaces, tabs, CR and LF; true if something is left.
  bool skip_space() {
    while (pos_ < text_.size() && is_space(text_[pos_])) ++pos_;
    return pos_ < text_.size();
  }
  /// Skips spaces, tabs and CR, but not LF.
  void skip_blank() {
    while (pos_ < text_.size() && (text_[pos_] == ' ' || text_[pos_] == '\t' || text_[pos_] == '\r')) ++pos_;
  }
  /// Skips the rest of the current line including its LF.
  void skip_line() {
    while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
    if (pos_ < text_.size()) ++pos_;
  }
  /// The next whitespace-delimited token; fails at the end of the file with `what`.
  std::string_view token(std::string_view what) {
    if (!skip_space()) fail("unexpected end of file, expected " + std::string(what));
    const std::size_t start = pos_;
    while (pos_ < text_.size() && !is_space(text_[pos_])) ++pos_;
    token_start_ = start;
    return text_.substr(start, pos_ - start);
  }
  /// Start of the last token (for error positions).
  std::size_t token_start() const { return token_start_; }

  void expect(std::string_view word) {
    const std::string_view t = token(word);
    if (t != word) fail_at(token_start_, "expected " + std::string(word) + ", got '" + shorten(t) + "'");
  }

  template <class T>
  T integer(std::string_view what) {
    static_assert(std::is_integral_v<T>);
    const std::string_view t = token(what);
    T v{};
    const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
    if (ec != std::errc() || end != t.data() + t.size())
      fail_at(token_start_, "expected " + std::string(what) + " (an integer), got '" + shorten(t) + "'");
    return v;
  }

  /// A double, possibly "nan" or "inf" (field values; coordinates use real()).
  double number(std::string_view what) {
    const std::string_view t = token(what);
    double v = 0;
    const char* b = t.data();
    if (!t.empty() && t[0] == '+') ++b;  // from_chars rejects a leading '+'
    const auto [end, ec] = std::from_chars(b, t.data() + t.size(), v);
    if (ec != std::errc() || end != t.data() + t.size())
      fail_at(token_start_, "expected " + std::string(what) + " (a number), got '" + shorten(t) + "'");
    return v;
  }

  /// A finite double.
  double real(std::string_view what) {
    const double v = number(what);
    if (!std::isfinite(v))
      fail_at(token_start_, std::string(what) + " is not finite: '" + shorten(text_.substr(token_start_, pos_ - token_start_)) + "'");
    return v;
  }

  /// A little-endian binary value of type T (the host is little-endian; checked by callers
  /// through the file's endianness marker).
  template <class T>
  T raw(std::string_view what) {
    if (text_.size() - pos_ < sizeof(T) || pos_ > text_.size())
      fail("unexpected end of file in binary data, expected " + std::string(what));
    T v;
    std::memcpy(&v, text_.data() + pos_, sizeof(T));
    token_start_ = pos_;  // messages about the value point at its first byte
    pos_ += sizeof(T);
    return v;
  }
  std::size_t remaining() const { return pos_ < text_.size() ? text_.size() - pos_ : 0; }

  static bool is_space(char c) { return c == ' ' || c == '\n' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }
  static std::string shorten(std::string_view t) {
    std::string s(t.substr(0, 40));
    for (char& c : s)
      if (static_cast<unsigned char>(c) < 32 || static_cast<unsigned char>(c) > 126) c = '?';
    if (t.size() > 40) s += "...";
    return s;
  }

 private:
  std::filesystem::path file_;
  std::string_view text_;
  std::size_t pos_ = 0;
  std::size_t token_start_ = 0;
};

}  // namespace meshmorph::detail
