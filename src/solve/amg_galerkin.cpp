// SPDX-License-Identifier: MIT
// The coarse operator of a multigrid level, R A P, with A P formed a slice of rows at a time.
#include <algorithm>

#include "solve/detail/amg_csr.h"

namespace meshmorph::detail {
namespace {

// A fixed count (not one per thread) keeps the hierarchy the same on any number of threads.
constexpr int kSlices = 16;

// C's pattern, node by node (nodes of `n` rows and columns, n = 1: entries): the coarse
// nodes K reached from coarse node I through R's fine nodes J, A's neighbours L of those
// (each L once: the fine nodes of R A's row) and P.
Csr galerkin_pattern(const SparseView& A, const Csr& P, const Csr& R, int n, int threads) {
  Csr C;
  C.rows = R.rows;
  C.cols = P.cols;
  const int n_nodes = R.rows / n;
  std::vector<std::vector<int>> blocks(static_cast<std::size_t>(n_nodes));
#pragma omp parallel num_threads(threads)
  {
    std::vector<int> seen(static_cast<std::size_t>(A.n / n), -1), marker(static_cast<std::size_t>(P.cols / n), -1);
    std::vector<int> fine;
#pragma omp for schedule(dynamic, 64)
    for (int I = 0; I < n_nodes; ++I) {
      fine.clear();
      for (int kr = R.ptr[I * n]; kr < R.ptr[I * n + 1]; kr += n) {
        const int j = R.idx[kr];
        for (int ka = A.outer[j]; ka < A.outer[j + 1]; ka += n)
          if (seen[A.inner[ka] / n] != I) seen[A.inner[ka] / n] = I, fine.push_back(A.inner[ka]);
      }
      std::vector<int>& row = blocks[static_cast<std::size_t>(I)];
      for (const int l : fine)
        for (int kp = P.ptr[l]; kp < P.ptr[l + 1]; kp += n) {
          const int K = P.idx[kp] / n;
          if (marker[K] != I) marker[K] = I, row.push_back(K);
        }
      std::sort(row.begin(), row.end());
    }
  }
  expand_node_pattern(n, blocks, C, threads);
  return C;
}

// Rows `first` .. `first + rows` of A P, nodes of N rows (A and P with block rows of N): the
// values multiply() gives them, each row's blocks in the order they are met (unsorted: the
// sort and the per-row lists of multiply()'s pattern took as long as the products).
// `count` (one per node row): the blocks of each row, counted here unless `known`.
template <int N>
Csr slice_product(const SparseView& A, const Csr& P, int first, int rows, int* count, bool known, int threads) {
  Csr S;
  S.rows = rows;
  S.cols = P.cols;
  const int n_nodes = rows / N, f = first / N;
#pragma omp parallel num_threads(threads) if (!known)
  if (!known) {
    std::vector<int> marker(static_cast<std::size_t>(P.cols / N), -1);
#pragma omp for schedule(dynamic, 64)
    for (int I = 0; I < n_nodes; ++I) {
      const int i = (f + I) * N;
      int c = 0;
      for (int ka = A.outer[i]; ka < A.outer[i + 1]; ka += N)
        for (int kb = P.ptr[A.inner[ka]]; kb < P.ptr[A.inner[ka] + 1]; kb += N)
          if (marker[P.idx[kb] / N] != I) marker[P.idx[kb] / N] = I, ++c;
      count[I] = c;
    }
  }
  S.ptr.assign(static_cast<std::size_t>(rows) + 1, 0);
  for (int I = 0; I < n_nodes; ++I)
    for (int r = 0; r < N; ++r) S.ptr[I * N + r + 1] = S.ptr[I * N + r] + N * count[I];
  S.idx.resize(static_cast<std::size_t>(S.ptr.back()));
  S.val.assign(static_cast<std::size_t>(S.ptr.back()), 0.0);
#pragma omp parallel num_threads(threads)
  {
    std::vector<int> slot(static_cast<std::size_t>(P.cols / N), -1);
#pragma omp for schedule(dynamic, 64)
    for (int I = 0; I < n_nodes; ++I) {
      const int i = (f + I) * N, s0 = S.ptr[I * N];
      double* srow[N];
      for (int r = 0; r < N; ++r) srow[r] = S.val.data() + S.ptr[I * N + r];
      int used = 0;
      for (int ka = A.outer[i]; ka < A.outer[i + 1]; ka += N) {
        double a[N][N];
        for (int r = 0; r < N; ++r)
          for (int m = 0; m < N; ++m) a[r][m] = A.values[A.outer[i + r] + (ka - A.outer[i]) + m];
        const int J = A.inner[ka];
        const int b0 = P.ptr[J], bw = P.ptr[J + 1] - b0;
        const double* brow[N];
        for (int m = 0; m < N; ++m) brow[m] = P.val.data() + P.ptr[J + m];
        for (int kb = 0; kb < bw; kb += N) {
          const int K = P.idx[b0 + kb] / N;
          if (slot[K] < 0) {
            slot[K] = used;
            for (int r = 0; r < N; ++r)
              for (int c = 0; c < N; ++c) S.idx[static_cast<std::size_t>(S.ptr[I * N + r] + used + c)] = K * N + c;
            used += N;
          }
          const int off = slot[K];
          add_block_product<N>(a, brow, kb, srow, off);
        }
      }
      for (int k = 0; k < used; k += N) slot[S.idx[static_cast<std::size_t>(s0 + k)] / N] = -1;
    }
  }
  return S;
}

}  // namespace

bool galerkin(const SparseView& A, const Csr& P, const Csr& R, int row_block, int block, Csr& C,
              std::vector<int>& ap_blocks, bool values_only, int threads) {
  // A P node by node where P has A's block rows too (as multiply() forms it).
  const int by_blocks = row_block > 1 && has_block_rows(P, row_block) ? row_block : 1;
  const auto n_rows = static_cast<std::size_t>(A.n / by_blocks);
  if (!values_only) {
    C = galerkin_pattern(A, P, R, block, threads);
    ap_blocks.assign(n_rows, 0);
  }
  if (C.rows != R.rows || C.cols != P.cols || ap_blocks.size() != n_rows) return false;
  std::fill(C.val.begin(), C.val.end(), 0.0);
  // Slices of whole nodes of A's rows and of R's columns.
  const int node = std::max(row_block, block);
  const int step = std::max(1, (A.n / node + kSlices - 1) / kSlices) * node;
  for (int first = 0; first < A.n; first += step) {
    const int rows = std::min(step, A.n - first);
    int* count = ap_blocks.data() + first / by_blocks;
    const Csr AP = by_blocks == 3   ? slice_product<3>(A, P, first, rows, count, values_only, threads)
                   : by_blocks == 2 ? slice_product<2>(A, P, first, rows, count, values_only, threads)
                                    : slice_product<1>(A, P, first, rows, count, values_only, threads);
    add_product(R, AP, first, C, block, threads);
  }
  return true;
}

}  // namespace meshmorph::detail
