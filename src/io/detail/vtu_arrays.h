// SPDX-License-Identifier: MIT
#pragma once
#include <cstddef>
#include <filesystem>
#include <optional>
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

/// The values of a DataArray (ascii, base64 binary or appended; zlib or not) converted to T
/// (double or std::int64_t); exactly `expected` values when given. Undecodable data, and
/// non-finite floats unless `allow_nonfinite` (field values), are an InputError at the
/// array's line.
template <class T>
std::vector<T> read_array(const VtuFile& f, const pugi::xml_node& node, std::optional<std::size_t> expected,
                          bool allow_nonfinite = false);

}  // namespace meshmorph::detail
