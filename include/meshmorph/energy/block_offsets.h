// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include <Eigen/SparseCore>

#include "meshmorph/energy/dof_map.h"

namespace meshmorph {

/// Where the diagonal blocks of nodes lie in a Hessian over the free DOFs of `dofs` (CSC,
/// sorted row indices, as EnergyAssembler builds it): for each node of `nodes` in turn, the
/// d² offsets into H's value array of the entries (dof k, dof l) of the node, index l·d + k
/// (column-major, d = dofs.dim()), −1 where dof k or dof l is fixed. Throws
/// std::invalid_argument when a free entry is missing from H's pattern.
std::vector<std::int64_t> diagonal_block_offsets(const DofMap& dofs, const Eigen::SparseMatrix<double>& H,
                                                 std::span<const std::int32_t> nodes);

}  // namespace meshmorph
