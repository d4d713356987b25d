// SPDX-License-Identifier: MIT
#include "meshmorph/methods/threads.h"

namespace meshmorph {

int default_threads(int requested, std::size_t n_dofs) {
  constexpr std::size_t k_min_parallel_dofs = 30000;
  return requested > 0 ? requested : n_dofs < k_min_parallel_dofs ? 1 : 0;
}

}  // namespace meshmorph
