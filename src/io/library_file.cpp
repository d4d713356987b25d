// SPDX-License-Identifier: MIT
#include "io/detail/library_file.h"

#include <fstream>
#include <system_error>

#include "meshmorph/error.h"
#include "meshmorph/io/input_files.h"

namespace meshmorph::detail {

void check_library_input(const std::filesystem::path& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw IoError(path.string() + ": is a folder, not a mesh file");
  if (!std::ifstream(path, std::ios::binary)) throw IoError(path.string() + ": cannot open for reading");
  note_input_file(path);
}

std::mutex& library_mutex() {
  static std::mutex m;
  return m;
}

}  // namespace meshmorph::detail
