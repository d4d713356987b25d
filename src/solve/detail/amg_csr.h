// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <vector>

#include "solve/detail/cholmod_solver.h"

namespace meshmorph::detail {

/// A rectangular sparse matrix in compressed rows with sorted column indices (the
/// multigrid's prolongators, restrictions and coarse operators).
struct Csr {
  int rows = 0;
  int cols = 0;
  std::vector<int> ptr{0};
  std::vector<int> idx;
  std::vector<double> val;
  std::int64_t nnz() const { return ptr.back(); }
  /// Square and symmetric storage read as a SparseView (rows = columns).
  SparseView view() const { return SparseView{rows, ptr.data(), idx.data(), val.data()}; }
};

/// Whether A's rows come in groups of b (a node's unknowns) that share one sorted pattern
/// made of whole b-column blocks (a neighbour's unknowns): what the `block` products need.
bool has_block_rows(const SparseView& A, int b);
bool has_block_rows(const Csr& A, int b);
/// y = A x over the rows of A (OpenMP, `threads` threads, static schedule).
void spmv(const SparseView& A, const double* x, double* y, int threads);
void spmv(const Csr& A, const double* x, double* y, int threads);
/// r = b − A x.
void residual(const SparseView& A, const double* b, const double* x, double* r, int threads);
/// The same products on a matrix with has_block_rows(A, block) (block = 1: the ones above).
/// A node's rows read each column index once for all of them: a third less memory traffic
/// for 3D Hessians, the multigrid cycle's bottleneck.
void spmv(const SparseView& A, int block, const double* x, double* y, int threads);
void spmv(const Csr& A, int block, const double* x, double* y, int threads);
void residual(const SparseView& A, int block, const double* b, const double* x, double* r, int threads);
/// Aᵀ (rows become columns), sorted.
Csr transpose(const Csr& A, int threads);
/// C = A B (Gustavson, two passes: row counts then values), rows of C sorted. A is rows × k
/// given as a view of a square matrix or a Csr; B is k × m. Where A and B both have block
/// rows of size `block` (has_block_rows), the pattern is found node by node and the values
/// block by block, as multiply_values() with that block computes them.
Csr multiply(const SparseView& A, const Csr& B, int block, int threads);
Csr multiply(const Csr& A, const Csr& B, int block, int threads);
/// C = A B again for new values of A or B of the same patterns: C keeps the pattern of the
/// multiply() that made it and only its values are recomputed. With block > 1, A, B and C
/// must all have block rows of that size (has_block_rows), and the product goes block by
/// block.
void multiply_values(const SparseView& A, const Csr& B, Csr& C, int block, int threads);
void multiply_values(const Csr& A, const Csr& B, Csr& C, int block, int threads);

/// C += A(:, first .. first + B.rows) B, B's rows numbered from `first`, into C's pattern
/// (which holds every entry of the product; A's rows sorted; `block` as multiply_values()): over
/// consecutive ranges of A's columns these add up to multiply_values()'s C to the last bit.
void add_product(const Csr& A, const Csr& B, int first, Csr& C, int block, int threads);
/// c_r[off + j] += Σ_m a[r][m] b_m[j] for the N×N block of b's rows at `kb`: the block step
/// of the products, whose order of sums multiply() and galerkin() share (the same bits).
template <int N>
inline void add_block_product(const double (&a)[N][N], const double* const (&b)[N], int kb, double* const (&c)[N],
                              int off) {
  for (int r = 0; r < N; ++r)
    for (int j = 0; j < N; ++j) {
      double s = 0.0;
      for (int m = 0; m < N; ++m) s += a[r][m] * b[m][kb + j];
      c[r][off + j] += s;
    }
}

/// C's pattern from one given node by node: C.rows rows in nodes of `n`, blocks[I] the sorted
/// column nodes of node row I, each an n×n block; values zero. Empties `blocks`.
void expand_node_pattern(int n, std::vector<std::vector<int>>& blocks, Csr& C, int threads);
/// The coarse operator C = R A P of a multigrid level (R = Pᵀ) with A P formed for a sixteenth
/// of A's rows at a time and added to C, so that it is never held whole (on the §5.2 shells
/// A P holds 1.1 entries per entry of A). `row_block`: the block rows of A and P; `block`:
/// those of R and A P for the second product. C comes out exactly as multiply(R, multiply(A,
/// P, row_block), block) computes it. `ap_blocks`: the blocks of each row of A P, filled by a
/// full product. With `values_only`, C and `ap_blocks` are those of an earlier galerkin() of
/// the same patterns and only C's values are recomputed (false where they do not fit).
bool galerkin(const SparseView& A, const Csr& P, const Csr& R, int row_block, int block, Csr& C,
              std::vector<int>& ap_blocks, bool values_only, int threads);

double dot(const double* a, const double* b, int n, int threads);

}  // namespace meshmorph::detail
