// SPDX-License-Identifier: MIT
#pragma once
#include <cstddef>
#include <filesystem>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include <pugixml.hpp>

#include "io/detail/cursor.h"

namespace meshmorph::detail {

/// What the DataArray decoder needs to know about a .vtu file.
struct VtuFile {
  std::filesystem::path path;
  std::string_view text;           // the whole file
  bool header64 = false;           // header_type UInt64
  bool compressed = false;         // vtkZLibDataCompressor
  std::size_t appended = std::string_view::npos;  // first byte after '_' in AppendedData
  std::size_t appended_end = 0;
  bool appended_base64 = false;
  std::vector<std::size_t> appended_offsets;  // sorted offsets of all appended arrays

  [[noreturn]] void fail(const pugi::xml_node& node, const std::string& msg) const {
    throw_input_error(path, text, static_cast<std::size_t>(std::max<std::ptrdiff_t>(0, node.offset_debug())),
                              false, msg);
  }
};

/// How many values a DataArray must hold: exactly `n`, or at most `n` (by default, any number).
struct ValueCount {
  std::size_t n = std::numeric_limits<std::size_t>::max();
  bool exact = false;
};
inline ValueCount exactly(std::size_t n) { return {n, true}; }
inline ValueCount at_most(std::size_t n) { return {n, false}; }

/// The values of a DataArray (ascii, base64 binary or appended; zlib or not) converted to T
/// (double or std::int64_t), as many as `count` allows. Undecodable data, a header that
/// announces more bytes than `count` allows or than its zlib blocks can inflate to (checked
/// before anything is allocated), and non-finite floats unless `allow_nonfinite` (field
/// values), are an InputError at the array's line.
template <class T>
std::vector<T> read_array(const VtuFile& f, const pugi::xml_node& node, ValueCount count, bool allow_nonfinite = false);

}  // namespace meshmorph::detail
