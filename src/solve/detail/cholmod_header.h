// SPDX-License-Identifier: MIT
#pragma once
#include <cholmod.h>

#include "solve/detail/cholmod_solver.h"

namespace meshmorph::detail {

/// A cholmod_sparse header over the arrays of a symmetric matrix stored with both triangles
/// (CHOLMOD reads its upper triangle, stype = 1, and does not write through the header).
inline cholmod_sparse cholmod_header(const SparseView& A) {
  cholmod_sparse s{};
  s.nrow = s.ncol = static_cast<std::size_t>(A.n);
  s.nzmax = static_cast<std::size_t>(A.nnz());
  s.p = const_cast<int*>(A.outer);
  s.i = const_cast<int*>(A.inner);
  s.x = const_cast<double*>(A.values);
  s.stype = 1;
  s.itype = CHOLMOD_INT;
  s.xtype = CHOLMOD_REAL;
  s.dtype = CHOLMOD_DOUBLE;
  s.sorted = 1;
  s.packed = 1;
  return s;
}

}  // namespace meshmorph::detail
