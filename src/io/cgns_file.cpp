// SPDX-License-Identifier: MIT
#include "io/detail/cgns_file.h"

#include <cgnslib.h>

#include "io/detail/library_file.h"
#include "meshmorph/error.h"

namespace meshmorph::detail {

CgnsFile::CgnsFile(const std::filesystem::path& file, bool write, const std::string& name) : write_(write), name_(name) {
  if (write) {
    if (cg_set_file_type(CG_FILE_HDF5) != CG_OK || cg_open(file.c_str(), CG_MODE_WRITE, &fn_) != CG_OK)
      throw IoError(name + ": cannot create the CGNS file: " + cg_get_error());
    return;
  }
  check_library_input(file);
  int type = 0;
  if (cg_is_cgns(file.c_str(), &type) != CG_OK) throw InputError(name + ": node /: not a CGNS file (neither HDF5 nor ADF)");
  if (cg_open(file.c_str(), CG_MODE_READ, &fn_) != CG_OK)
    throw InputError(name + ": node /: cannot be read as CGNS: " + cg_get_error());
}

CgnsFile::~CgnsFile() {
  if (fn_ >= 0) cg_close(fn_);
}

void CgnsFile::check(int status, const std::string& where) const {
  if (status == CG_OK) return;
  const std::string msg = name_ + ": " + where + ": " + cg_get_error();
  if (write_) throw IoError(msg);
  throw InputError(msg);
}

}  // namespace meshmorph::detail
