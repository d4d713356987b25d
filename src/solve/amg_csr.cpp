// SPDX-License-Identifier: MIT
#include "solve/detail/amg_csr.h"

#include <algorithm>
#include <numeric>

namespace meshmorph::detail {
namespace {

struct RowsView {
  int rows, cols;
  const int* ptr;
  const int* idx;
  const double* val;
};

RowsView rows_of(const SparseView& A) { return {A.n, A.n, A.outer, A.inner, A.values}; }
bool block_rows_of(const RowsView& A, int b);
RowsView rows_of(const Csr& A) { return {A.rows, A.cols, A.ptr.data(), A.idx.data(), A.val.data()}; }

void spmv_rows(const RowsView& A, const double* x, double* y, int threads) {
#pragma omp parallel for num_threads(threads) schedule(static)
  for (int i = 0; i < A.rows; ++i) {
    double s = 0.0;
    for (int k = A.ptr[i]; k < A.ptr[i + 1]; ++k) s += A.val[k] * x[A.idx[k]];
    y[i] = s;
  }
}

// Gustavson's row-by-row product with one dense marker per thread: the first pass counts the
// distinct columns of each row of C, the second fills them and sorts each row.
Csr multiply_rows(const RowsView& A, const Csr& B, int threads) {
  Csr C;
  C.rows = A.rows;
  C.cols = B.cols;
  std::vector<int> count(static_cast<std::size_t>(A.rows) + 1, 0);
#pragma omp parallel num_threads(threads)
  {
    std::vector<int> marker(static_cast<std::size_t>(B.cols), -1);
#pragma omp for schedule(dynamic, 256)
    for (int i = 0; i < A.rows; ++i) {
      int c = 0;
      for (int ka = A.ptr[i]; ka < A.ptr[i + 1]; ++ka) {
        const int j = A.idx[ka];
        for (int kb = B.ptr[j]; kb < B.ptr[j + 1]; ++kb)
          if (marker[B.idx[kb]] != i) marker[B.idx[kb]] = i, ++c;
      }
      count[i + 1] = c;
    }
  }
  std::partial_sum(count.begin(), count.end(), count.begin());
  C.ptr = std::move(count);
  C.idx.resize(static_cast<std::size_t>(C.ptr.back()));
  C.val.resize(static_cast<std::size_t>(C.ptr.back()));
#pragma omp parallel num_threads(threads)
  {
    std::vector<int> slot(static_cast<std::size_t>(B.cols), -1);
    std::vector<std::pair<int, double>> row;
#pragma omp for schedule(dynamic, 256)
    for (int i = 0; i < A.rows; ++i) {
      row.clear();
      for (int ka = A.ptr[i]; ka < A.ptr[i + 1]; ++ka) {
        const int j = A.idx[ka];
        const double a = A.val[ka];
        for (int kb = B.ptr[j]; kb < B.ptr[j + 1]; ++kb) {
          const int col = B.idx[kb];
          if (slot[col] < 0) {
            slot[col] = static_cast<int>(row.size());
            row.emplace_back(col, a * B.val[kb]);
          } else {
            row[static_cast<std::size_t>(slot[col])].second += a * B.val[kb];
          }
        }
      }
      std::sort(row.begin(), row.end());
      int k = C.ptr[i];
      for (const auto& [col, v] : row) {
        slot[col] = -1;
        C.idx[k] = col;
        C.val[k++] = v;
      }
    }
  }
  return C;
}

// C += A(:, first .. first + B.rows) B (B's rows numbered from `first`) into C's pattern,
// which holds every entry of the product, in N×N blocks of rows with block rows of size N
// (block_rows_of; N = 1: entry by entry): one slot lookup and N³ multiply-adds a pair of
// blocks instead of N² lookups. A's entries are taken in their order, so that the products
// over consecutive ranges of A's columns add up to the whole one to the last bit.
template <int N>
void add_products(const RowsView& A, const Csr& B, int first, Csr& C, int threads) {
  const int last = first + B.rows;
#pragma omp parallel num_threads(threads)
  {
    std::vector<int> slot(static_cast<std::size_t>(C.cols / N), -1);
#pragma omp for schedule(dynamic, 64)
    for (int I = 0; I < A.rows / N; ++I) {
      const int* begin = A.idx + A.ptr[I * N];
      const int* end = A.idx + A.ptr[I * N + 1];
      const int k0 = static_cast<int>(std::lower_bound(begin, end, first) - begin);
      const int k1 = static_cast<int>(std::lower_bound(begin, end, last) - begin);
      if (k0 == k1) continue;
      const int c0 = C.ptr[I * N], cw = C.ptr[I * N + 1] - c0;
      double* crow[N];
      for (int r = 0; r < N; ++r) crow[r] = C.val.data() + C.ptr[I * N + r];
      for (int k = 0; k < cw; k += N) slot[C.idx[c0 + k] / N] = k;
      for (int ka = k0; ka < k1; ka += N) {
        double a[N][N];
        for (int r = 0; r < N; ++r)
          for (int m = 0; m < N; ++m) a[r][m] = A.val[A.ptr[I * N + r] + ka + m];
        const int J = (begin[ka] - first) / N;
        const int b0 = B.ptr[J * N], bw = B.ptr[J * N + 1] - b0;
        const double* brow[N];
        for (int m = 0; m < N; ++m) brow[m] = B.val.data() + B.ptr[J * N + m];
        for (int kb = 0; kb < bw; kb += N) add_block_product<N>(a, brow, kb, crow, slot[B.idx[b0 + kb] / N]);
      }
    }
  }
}

void add_products_of(const RowsView& A, const Csr& B, int first, Csr& C, int block, int threads) {
  if (block == 3) return add_products<3>(A, B, first, C, threads);
  if (block == 2) return add_products<2>(A, B, first, C, threads);
  add_products<1>(A, B, first, C, threads);
}

// C = A B for A and B with block rows of size N: the pattern node by node (one marker per
// block instead of per entry, each row's blocks sorted), expanded to whole N×N blocks, then
// the values block by block.
template <int N>
Csr multiply_blocks(const RowsView& A, const Csr& B, int threads) {
  Csr C;
  C.rows = A.rows;
  C.cols = B.cols;
  const int n_nodes = A.rows / N;
  std::vector<std::vector<int>> blocks(static_cast<std::size_t>(n_nodes));  // column nodes of each node row
#pragma omp parallel num_threads(threads)
  {
    std::vector<int> marker(static_cast<std::size_t>(B.cols / N), -1);
#pragma omp for schedule(dynamic, 256)
    for (int I = 0; I < n_nodes; ++I) {
      std::vector<int>& row = blocks[static_cast<std::size_t>(I)];
      for (int ka = A.ptr[I * N]; ka < A.ptr[I * N + 1]; ka += N) {
        const int J = A.idx[ka] / N;
        for (int kb = B.ptr[J * N]; kb < B.ptr[J * N + 1]; kb += N) {
          const int K = B.idx[kb] / N;
          if (marker[K] != I) marker[K] = I, row.push_back(K);
        }
      }
      std::sort(row.begin(), row.end());
    }
  }
  expand_node_pattern(N, blocks, C, threads);
  add_products<N>(A, B, 0, C, threads);
  return C;
}

Csr multiply_of(const RowsView& A, const Csr& B, int block, int threads) {
  if (block > 1 && block_rows_of(A, block) && block_rows_of(rows_of(B), block)) {
    if (block == 3) return multiply_blocks<3>(A, B, threads);
    if (block == 2) return multiply_blocks<2>(A, B, threads);
  }
  return multiply_rows(A, B, threads);
}

void multiply_values_of(const RowsView& A, const Csr& B, Csr& C, int block, int threads) {
  std::fill(C.val.begin(), C.val.end(), 0.0);
  add_products_of(A, B, 0, C, block, threads);
}

// has_block_rows over any compressed rows (square or not).
bool block_rows_of(const RowsView& A, int b) {
  if (b < 2 || A.rows % b != 0 || A.cols % b != 0) return false;
  for (int I = 0; I < A.rows / b; ++I) {
    const int first = A.ptr[I * b], width = A.ptr[I * b + 1] - first;
    if (width % b != 0) return false;
    for (int r = 1; r < b; ++r) {
      const int row = A.ptr[I * b + r];
      if (A.ptr[I * b + r + 1] - row != width || !std::equal(A.idx + first, A.idx + first + width, A.idx + row))
        return false;
    }
    for (int k = 0; k < width; k += b)
      for (int c = 1; c < b; ++c)
        if (A.idx[first + k + c] != A.idx[first + k] + c || A.idx[first + k] % b != 0) return false;
  }
  return true;
}

}  // namespace

void expand_node_pattern(int n, std::vector<std::vector<int>>& blocks, Csr& C, int threads) {
  const auto n_nodes = static_cast<int>(blocks.size());
  C.ptr.assign(static_cast<std::size_t>(C.rows) + 1, 0);
  for (int I = 0; I < n_nodes; ++I)
    for (int r = 0; r < n; ++r)
      C.ptr[I * n + r + 1] = C.ptr[I * n + r] + n * static_cast<int>(blocks[static_cast<std::size_t>(I)].size());
  C.idx.resize(static_cast<std::size_t>(C.ptr.back()));
  C.val.assign(static_cast<std::size_t>(C.ptr.back()), 0.0);
#pragma omp parallel for num_threads(threads) schedule(static)
  for (int I = 0; I < n_nodes; ++I) {
    std::vector<int>& row = blocks[static_cast<std::size_t>(I)];
    for (int r = 0; r < n; ++r) {
      int k = C.ptr[I * n + r];
      for (const int K : row)
        for (int c = 0; c < n; ++c) C.idx[static_cast<std::size_t>(k++)] = K * n + c;
    }
    std::vector<int>().swap(row);
  }
}

void add_product(const Csr& A, const Csr& B, int first, Csr& C, int block, int threads) {
  add_products_of(rows_of(A), B, first, C, block, threads);
}

void multiply_values(const SparseView& A, const Csr& B, Csr& C, int block, int threads) {
  multiply_values_of(rows_of(A), B, C, block, threads);
}
void multiply_values(const Csr& A, const Csr& B, Csr& C, int block, int threads) {
  multiply_values_of(rows_of(A), B, C, block, threads);
}

void spmv(const SparseView& A, const double* x, double* y, int threads) { spmv_rows(rows_of(A), x, y, threads); }
void spmv(const Csr& A, const double* x, double* y, int threads) { spmv_rows(rows_of(A), x, y, threads); }

void residual(const SparseView& A, const double* b, const double* x, double* r, int threads) {
#pragma omp parallel for num_threads(threads) schedule(static)
  for (int i = 0; i < A.n; ++i) {
    double s = b[i];
    for (int k = A.outer[i]; k < A.outer[i + 1]; ++k) s -= A.values[k] * x[A.inner[k]];
    r[i] = s;
  }
}

bool has_block_rows(const SparseView& A, int b) { return block_rows_of(rows_of(A), b); }
bool has_block_rows(const Csr& A, int b) { return block_rows_of(rows_of(A), b); }

namespace {

// y = (b or 0) + s·A x over the node rows of a matrix with B×B block rows: the column of a
// block comes from the node's first row, its values from each of the node's rows.
template <int B>
void block_rows(const RowsView& A, const double* b, const double* x, double* y, double s, int threads) {
#pragma omp parallel for num_threads(threads) schedule(static)
  for (int I = 0; I < A.rows / B; ++I) {
    const int first = A.ptr[I * B], width = A.ptr[I * B + 1] - first;
    const double* row[B];
    for (int r = 0; r < B; ++r) row[r] = A.val + A.ptr[I * B + r];
    double acc[B] = {};
    for (int k = 0; k < width; k += B) {
      const double* xj = x + A.idx[first + k];
      for (int r = 0; r < B; ++r)
        for (int c = 0; c < B; ++c) acc[r] += row[r][k + c] * xj[c];
    }
    for (int r = 0; r < B; ++r) y[I * B + r] = (b ? b[I * B + r] : 0.0) + s * acc[r];
  }
}

}  // namespace

void spmv(const SparseView& A, int block, const double* x, double* y, int threads) {
  if (block == 3) return block_rows<3>(rows_of(A), nullptr, x, y, 1.0, threads);
  if (block == 2) return block_rows<2>(rows_of(A), nullptr, x, y, 1.0, threads);
  spmv(A, x, y, threads);
}

void spmv(const Csr& A, int block, const double* x, double* y, int threads) {
  if (block == 3) return block_rows<3>(rows_of(A), nullptr, x, y, 1.0, threads);
  if (block == 2) return block_rows<2>(rows_of(A), nullptr, x, y, 1.0, threads);
  spmv(A, x, y, threads);
}

void residual(const SparseView& A, int block, const double* b, const double* x, double* r, int threads) {
  if (block == 3) return block_rows<3>(rows_of(A), b, x, r, -1.0, threads);
  if (block == 2) return block_rows<2>(rows_of(A), b, x, r, -1.0, threads);
  residual(A, b, x, r, threads);
}

Csr transpose(const Csr& A, int /*threads*/) {
  Csr T;
  T.rows = A.cols;
  T.cols = A.rows;
  T.ptr.assign(static_cast<std::size_t>(A.cols) + 1, 0);
  for (std::int64_t k = 0; k < A.nnz(); ++k) ++T.ptr[A.idx[k] + 1];
  std::partial_sum(T.ptr.begin(), T.ptr.end(), T.ptr.begin());
  T.idx.resize(A.idx.size());
  T.val.resize(A.val.size());
  std::vector<int> next(T.ptr.begin(), T.ptr.end() - 1);
  // Rows of A in increasing order, so each row of Aᵀ comes out sorted.
  for (int i = 0; i < A.rows; ++i)
    for (int k = A.ptr[i]; k < A.ptr[i + 1]; ++k) {
      const int slot = next[A.idx[k]]++;
      T.idx[slot] = i;
      T.val[slot] = A.val[k];
    }
  return T;
}

Csr multiply(const SparseView& A, const Csr& B, int block, int threads) { return multiply_of(rows_of(A), B, block, threads); }
Csr multiply(const Csr& A, const Csr& B, int block, int threads) { return multiply_of(rows_of(A), B, block, threads); }

double dot(const double* a, const double* b, int n, int threads) {
  double s = 0.0;
#pragma omp parallel for num_threads(threads) schedule(static) reduction(+ : s)
  for (int i = 0; i < n; ++i) s += a[i] * b[i];
  return s;
}

}  // namespace meshmorph::detail
