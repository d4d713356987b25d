// SPDX-License-Identifier: MIT
#pragma once
#include <omp.h>

namespace meshmorph {

/// The OpenMP thread count a run uses: `threads` when positive, else the OpenMP default
/// (omp_get_max_threads(): OMP_NUM_THREADS, or every core).
inline int resolve_threads(int threads) { return threads > 0 ? threads : omp_get_max_threads(); }

}  // namespace meshmorph
