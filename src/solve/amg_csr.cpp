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
