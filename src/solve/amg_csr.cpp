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

}  // namespace

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

bool has_block_rows(const SparseView& A, int b) {
  if (b < 2 || A.n % b != 0) return false;
  for (int I = 0; I < A.n / b; ++I) {
    const int first = A.outer[I * b], width = A.outer[I * b + 1] - first;
    if (width % b != 0) return false;
    for (int r = 1; r < b; ++r) {
      const int row = A.outer[I * b + r];
      if (A.outer[I * b + r + 1] - row != width || !std::equal(A.inner + first, A.inner + first + width, A.inner + row))
        return false;
    }
    for (int k = 0; k < width; k += b)
      for (int c = 1; c < b; ++c)
        if (A.inner[first + k + c] != A.inner[first + k] + c || A.inner[first + k] % b != 0) return false;
  }
  return true;
}

namespace {

// y = (b or 0) + s·A x over the node rows of a matrix with B×B block rows: the column of a
// block comes from the node's first row, its values from each of the node's rows.
template <int B>
void block_rows(const SparseView& A, const double* b, const double* x, double* y, double s, int threads) {
#pragma omp parallel for num_threads(threads) schedule(static)
  for (int I = 0; I < A.n / B; ++I) {
    const int first = A.outer[I * B], width = A.outer[I * B + 1] - first;
    const double* row[B];
    for (int r = 0; r < B; ++r) row[r] = A.values + A.outer[I * B + r];
    double acc[B] = {};
    for (int k = 0; k < width; k += B) {
      const double* xj = x + A.inner[first + k];
      for (int r = 0; r < B; ++r)
        for (int c = 0; c < B; ++c) acc[r] += row[r][k + c] * xj[c];
    }
    for (int r = 0; r < B; ++r) y[I * B + r] = (b ? b[I * B + r] : 0.0) + s * acc[r];
  }
}

}  // namespace

void spmv(const SparseView& A, int block, const double* x, double* y, int threads) {
  if (block == 3) return block_rows<3>(A, nullptr, x, y, 1.0, threads);
  if (block == 2) return block_rows<2>(A, nullptr, x, y, 1.0, threads);
  spmv(A, x, y, threads);
}

void residual(const SparseView& A, int block, const double* b, const double* x, double* r, int threads) {
  if (block == 3) return block_rows<3>(A, b, x, r, -1.0, threads);
  if (block == 2) return block_rows<2>(A, b, x, r, -1.0, threads);
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

Csr multiply(const SparseView& A, const Csr& B, int threads) { return multiply_rows(rows_of(A), B, threads); }
Csr multiply(const Csr& A, const Csr& B, int threads) { return multiply_rows(rows_of(A), B, threads); }

double dot(const double* a, const double* b, int n, int threads) {
  double s = 0.0;
#pragma omp parallel for num_threads(threads) schedule(static) reduction(+ : s)
  for (int i = 0; i < n; ++i) s += a[i] * b[i];
  return s;
}

}  // namespace meshmorph::detail
