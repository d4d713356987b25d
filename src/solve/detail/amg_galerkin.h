// SPDX-License-Identifier: MIT
#pragma once
#include <vector>

#include "solve/detail/amg_csr.h"

namespace meshmorph::detail {

/// The node pattern of A P: for each node row of A, its coarse nodes in increasing order.
struct NodePattern {
  std::vector<int> ptr{0};
  std::vector<int> col;
};

/// The Galerkin operator C = R A P of matrices with block rows of size `block` (2 or 3;
/// has_block_rows of all three), without storing A P: `ap` gets A P's node pattern (one index
/// per node block where A P itself would take block² values and indices), C its pattern and
/// values (galerkin_values). C equals multiply(R, multiply(A, P, block), block) bit for bit.
Csr galerkin(const Csr& R, const SparseView& A, const Csr& P, int block, NodePattern& ap, int threads);

/// C's values for new values of A (same patterns as at galerkin): the rows of A P that a
/// chunk of `chunk` node rows of C needs are formed in a buffer of the thread's, block by
/// block in the order of multiply_values, so C equals multiply_values(R, multiply_values(A,
/// P)) bit for bit. Fine rows shared by two chunks are formed twice: a chunk of 512 coarse
/// nodes keeps that to a few percent while its buffer stays a small part of A P on large
/// meshes.
void galerkin_values(const Csr& R, const SparseView& A, const Csr& P, const NodePattern& ap, Csr& C, int block,
                     int threads, int chunk = 512);

}  // namespace meshmorph::detail
