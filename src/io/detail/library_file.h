// SPDX-License-Identifier: MIT
#pragma once
#include <filesystem>
#include <mutex>

namespace meshmorph::detail {

/// Checks, before a C library (CGNS, Exodus II) opens `path` by name, that it is a readable
/// file (IoError "is a folder, not a mesh file" / "cannot open for reading" otherwise), and
/// notes it as an input (io/input_files.h).
void check_library_input(const std::filesystem::path& path);

/// Held while a CGNS or Exodus II file is open: neither library (nor HDF5 and netCDF below
/// them, which they share) is thread-safe.
std::mutex& library_mutex();

}  // namespace meshmorph::detail
