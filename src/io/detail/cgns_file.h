// SPDX-License-Identifier: MIT
#pragma once
#include <filesystem>
#include <string>

namespace meshmorph::detail {

/// An open CGNS file (cg_open), closed by the destructor. The library reports errors through
/// return codes and cg_get_error, never by exiting.
class CgnsFile {
 public:
  /// Opens `file` for reading (CG_MODE_READ) or writing (CG_MODE_WRITE, HDF5). Reading a
  /// file that is not CGNS throws InputError ("<name>: not a CGNS file …"), writing one
  /// that cannot be created IoError; `name` is the file named in messages.
  CgnsFile(const std::filesystem::path& file, bool write, const std::string& name);
  ~CgnsFile();
  CgnsFile(const CgnsFile&) = delete;
  CgnsFile& operator=(const CgnsFile&) = delete;

  int fn() const { return fn_; }
  /// Throws when a CGNS call failed (status ≠ CG_OK): InputError when reading, IoError when
  /// writing, "<name>: <where>: <the library's message>".
  void check(int status, const std::string& where) const;
  const std::string& name() const { return name_; }

 private:
  int fn_ = -1;
  bool write_ = false;
  std::string name_;
};

}  // namespace meshmorph::detail
