// SPDX-License-Identifier: MIT
#include "io/detail/exodus_file.h"

#include <exodusII.h>

#include "io/detail/library_file.h"
#include "meshmorph/error.h"

namespace meshmorph::detail {
namespace {

std::string last_error() {
  const char* msg = nullptr;
  const char* func = nullptr;
  int code = 0;
  ex_get_err(&msg, &func, &code);
  return msg && *msg ? std::string(msg) : "error " + std::to_string(code);
}

}  // namespace

ExodusFile::ExodusFile(const std::filesystem::path& file, bool write, const std::string& name) : write_(write), name_(name) {
  ex_opts(EX_DEFAULT);
  int cpu_ws = sizeof(double), io_ws = sizeof(double);
  if (write) {
    id_ = ex_create(file.c_str(), EX_CLOBBER, &cpu_ws, &io_ws);
    if (id_ < 0) throw IoError(name + ": cannot create the Exodus II file: " + last_error());
    return;
  }
  check_library_input(file);
  io_ws = 0;
  float version = 0;
  id_ = ex_open(file.c_str(), EX_READ, &cpu_ws, &io_ws, &version);
  if (id_ < 0) throw InputError(name + ": header: not an Exodus II (netCDF) file: " + last_error());
}

ExodusFile::~ExodusFile() {
  if (id_ >= 0) ex_close(id_);
}

void ExodusFile::check(int status, const std::string& where) const {
  if (status >= 0) return;
  const std::string msg = name_ + ": " + where + ": " + last_error();
  if (write_) throw IoError(msg);
  throw InputError(msg);
}

}  // namespace meshmorph::detail
