// SPDX-License-Identifier: MIT
#pragma once
#include <charconv>
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
  /// VTKFile version below 2.1: Lagrange hexahedra in VTK 8's numbering, whose edges 10 and
  /// 11 VTK 9 swapped (VTK's XML reader converts such files the same way).
  bool hexahedra_v8 = false;

  [[noreturn]] void fail(const pugi::xml_node& node, const std::string& msg) const {
    throw_input_error(path, text, static_cast<std::size_t>(std::max<std::ptrdiff_t>(0, node.offset_debug())),
                              false, msg);
  }
  /// The `offset` attribute of an appended DataArray: decimal digits only (pugixml's
  /// as_ullong would take "-5" or "12abc" as some number).
  std::size_t appended_offset(const pugi::xml_node& node) const {
    const std::string_view t = node.attribute("offset").as_string();
    std::size_t v = 0;
    const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
    if (t.empty() || ec != std::errc() || end != t.data() + t.size())
      fail(node, "DataArray offset '" + std::string(t) + "' is not a byte offset (a non-negative integer)");
    return v;
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
