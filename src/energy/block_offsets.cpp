// SPDX-License-Identifier: MIT
#include "meshmorph/energy/block_offsets.h"

#include <algorithm>

#include "meshmorph/error.h"

namespace meshmorph {

std::vector<std::int64_t> diagonal_block_offsets(const DofMap& dofs, const Eigen::SparseMatrix<double>& H,
                                                 std::span<const std::int32_t> nodes) {
  const int d = dofs.dim();
  std::vector<std::int64_t> offsets;
  offsets.reserve(nodes.size() * static_cast<std::size_t>(d * d));
  for (std::int32_t s : nodes)
    for (int l = 0; l < d; ++l)
      for (int k = 0; k < d; ++k) {
        const std::int32_t row = dofs.reduced(static_cast<std::size_t>(d) * s + k);
        const std::int32_t col = dofs.reduced(static_cast<std::size_t>(d) * s + l);
        std::int64_t offset = -1;
        if (row >= 0 && col >= 0) {
          const int* begin = H.innerIndexPtr() + H.outerIndexPtr()[col];
          const int* end = H.innerIndexPtr() + H.outerIndexPtr()[col + 1];
          const int* it = std::lower_bound(begin, end, row);
          MESHMORPH_CHECK(it != end && *it == row, "diagonal_block_offsets: a node block is missing from the Hessian pattern");
          offset = it - H.innerIndexPtr();
        }
        offsets.push_back(offset);
      }
  return offsets;
}

}  // namespace meshmorph
