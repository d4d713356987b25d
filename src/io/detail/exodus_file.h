// SPDX-License-Identifier: MIT
#pragma once
#include <filesystem>
#include <string>

namespace meshmorph::detail {

/// An open Exodus II file (ex_open / ex_create, double precision, quiet: the library neither
/// prints nor exits on errors), closed by the destructor.
class ExodusFile {
 public:
  /// Reading a file that is not Exodus II throws InputError ("<name>: header: …"); creating
  /// one that cannot be written IoError; `name` is the file named in messages.
  ExodusFile(const std::filesystem::path& file, bool write, const std::string& name);
  ~ExodusFile();
  ExodusFile(const ExodusFile&) = delete;
  ExodusFile& operator=(const ExodusFile&) = delete;

  int id() const { return id_; }
  /// Throws when an Exodus call failed (status < 0): InputError when reading, IoError when
  /// writing, "<name>: <where>: <the library's message>".
  void check(int status, const std::string& where) const;
  const std::string& name() const { return name_; }

 private:
  int id_ = -1;
  bool write_ = false;
  std::string name_;
};

}  // namespace meshmorph::detail
