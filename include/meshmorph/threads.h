// SPDX-License-Identifier: MIT
#pragma once
#include <omp.h>

namespace meshmorph {

/// The OpenMP thread count a run uses: `threads` when positive, else the OpenMP default
/// (omp_get_max_threads(): OMP_NUM_THREADS, or every core).
inline int resolve_threads(int threads) { return threads > 0 ? threads : omp_get_max_threads(); }

/// omp_set_num_threads(threads) on the calling thread for the lifetime of the object (when
/// threads > 0), then its setting back: a call given a thread count holds to it in every
/// parallel region inside, Eigen's matrix products included, and leaves its caller's as it was.
class ScopedThreads {
 public:
  explicit ScopedThreads(int threads) : previous_(omp_get_max_threads()) {
    if (threads > 0) omp_set_num_threads(threads);
  }
  ~ScopedThreads() { omp_set_num_threads(previous_); }
  ScopedThreads(const ScopedThreads&) = delete;
  ScopedThreads& operator=(const ScopedThreads&) = delete;

 private:
  int previous_;
};

}  // namespace meshmorph
