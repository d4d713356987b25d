// SPDX-License-Identifier: MIT
#include "io/detail/cursor.h"

#include <algorithm>
#include <fstream>
#include <system_error>

#include "meshmorph/error.h"
#include "meshmorph/io/input_files.h"

namespace meshmorph::detail {

std::string read_file(const std::filesystem::path& path) {
  // An ifstream opens a folder too, and gives its size as LLONG_MAX.
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw IoError(path.string() + ": is a folder, not a mesh file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(path.string() + ": cannot open for reading");
  note_input_file(path);
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  if (size < 0) throw IoError(path.string() + ": cannot determine the file size");
  std::string data(static_cast<std::size_t>(size), '\0');
  in.seekg(0, std::ios::beg);
  if (size > 0 && !in.read(data.data(), size)) throw IoError(path.string() + ": read error");
  return data;
}

std::size_t line_of(std::string_view text, std::size_t offset) {
  offset = std::min(offset, text.size());
  return 1 + static_cast<std::size_t>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(offset), '\n'));
}

std::string location(const std::filesystem::path& file, std::string_view text, std::size_t offset, bool binary) {
  if (binary) return file.string() + ": byte offset " + std::to_string(offset);
  return file.string() + ": line " + std::to_string(line_of(text, offset));
}

void throw_input_error(const std::filesystem::path& file, std::string_view text, std::size_t offset,
                       bool binary, const std::string& msg) {
  throw InputError(location(file, text, offset, binary) + ": " + msg);
}

std::string Cursor::where(std::size_t offset) const { return location(file_, text_, offset, binary); }

}  // namespace meshmorph::detail
