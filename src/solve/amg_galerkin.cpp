// SPDX-License-Identifier: MIT
#include "solve/detail/amg_galerkin.h"

#include <algorithm>

namespace meshmorph::detail {
namespace {


// A P's node pattern: per node row J of A, the coarse nodes of P's rows in A's row J.
template <int N>
NodePattern node_pattern(const SparseView& A, const Csr& P, int threads) {
  const int n_nodes = A.n / N;
  std::vector<std::vector<int>> rows(static_cast<std::size_t>(n_nodes));
#pragma omp parallel num_threads(threads)
  {
    std::vector<int> marker(static_cast<std::size_t>(P.cols / N), -1);
#pragma omp for schedule(dynamic, 256)
    for (int J = 0; J < n_nodes; ++J) {
      std::vector<int>& row = rows[static_cast<std::size_t>(J)];
      for (int ka = A.outer[J * N]; ka < A.outer[J * N + 1]; ka += N) {
        const int M = A.inner[ka] / N;
        for (int kp = P.ptr[M * N]; kp < P.ptr[M * N + 1]; kp += N) {
          const int K = P.idx[kp] / N;
          if (marker[K] != J) marker[K] = J, row.push_back(K);
        }
      }
      std::sort(row.begin(), row.end());
    }
  }
  NodePattern ap;
  ap.ptr.resize(static_cast<std::size_t>(n_nodes) + 1);
  for (int J = 0; J < n_nodes; ++J) ap.ptr[J + 1] = ap.ptr[J] + static_cast<int>(rows[static_cast<std::size_t>(J)].size());
  ap.col.reserve(static_cast<std::size_t>(ap.ptr.back()));
  for (auto& row : rows) {
    ap.col.insert(ap.col.end(), row.begin(), row.end());
    std::vector<int>().swap(row);
  }
  return ap;
}

// C's pattern node by node, Ĉ_I = ∪ over R's blocks (I, J) of A P's row J, expanded to whole blocks.
template <int N>
Csr galerkin_pattern(const Csr& R, const NodePattern& ap, int n_coarse, int threads) {
  const int rows = R.rows / N;
  std::vector<std::vector<int>> nodes(static_cast<std::size_t>(rows));
#pragma omp parallel num_threads(threads)
  {
    std::vector<int> marker(static_cast<std::size_t>(n_coarse), -1);
#pragma omp for schedule(dynamic, 256)
    for (int I = 0; I < rows; ++I) {
      std::vector<int>& row = nodes[static_cast<std::size_t>(I)];
      for (int kr = R.ptr[I * N]; kr < R.ptr[I * N + 1]; kr += N) {
        const int J = R.idx[kr] / N;
        for (int k = ap.ptr[J]; k < ap.ptr[J + 1]; ++k)
          if (marker[ap.col[k]] != I) marker[ap.col[k]] = I, row.push_back(ap.col[k]);
      }
      std::sort(row.begin(), row.end());
    }
  }
  Csr C;
  C.rows = R.rows;
  C.cols = N * n_coarse;
  C.ptr.assign(static_cast<std::size_t>(C.rows) + 1, 0);
  for (int I = 0; I < rows; ++I)
    for (int r = 0; r < N; ++r)
      C.ptr[I * N + r + 1] = C.ptr[I * N + r] + N * static_cast<int>(nodes[static_cast<std::size_t>(I)].size());
  C.idx.resize(static_cast<std::size_t>(C.ptr.back()));
  C.val.resize(static_cast<std::size_t>(C.ptr.back()));
#pragma omp parallel for num_threads(threads) schedule(static)
  for (int I = 0; I < rows; ++I)
    for (int r = 0; r < N; ++r) {
      int k = C.ptr[I * N + r];
      for (const int K : nodes[static_cast<std::size_t>(I)])
        for (int c = 0; c < N; ++c) C.idx[static_cast<std::size_t>(k++)] = K * N + c;
    }
  return C;
}

template <int N>
void galerkin_values_of(const Csr& R, const SparseView& A, const Csr& P, const NodePattern& ap, Csr& C, int chunk,
                        int threads) {
  const int rows = R.rows / N;
  const int n_fine = A.n / N;
#pragma omp parallel num_threads(threads)
  {
    std::vector<int> local(static_cast<std::size_t>(n_fine), -1);  // fine node → its row in `buffer`
    std::vector<int> fine;                                          // the chunk's fine nodes
    std::vector<std::size_t> start;                                 // first value of each in `buffer`
    std::vector<double> buffer;                                     // A P's rows, N×N blocks row-major
    std::vector<int> slot(static_cast<std::size_t>(C.cols / N), -1);
#pragma omp for schedule(dynamic, 1)
    for (int I0 = 0; I0 < rows; I0 += chunk) {
      const int I1 = std::min(rows, I0 + chunk);
      fine.clear();
      start.assign(1, 0);
      for (int I = I0; I < I1; ++I)
        for (int kr = R.ptr[I * N]; kr < R.ptr[I * N + 1]; kr += N) {
          const int J = R.idx[kr] / N;
          if (local[J] >= 0) continue;
          local[J] = static_cast<int>(fine.size());
          fine.push_back(J);
          start.push_back(start.back() + static_cast<std::size_t>(ap.ptr[J + 1] - ap.ptr[J]) * N * N);
        }
      buffer.assign(start.back(), 0.0);
      // Rows of A P, as multiply_values forms them: A's blocks in order, P's blocks in order.
      for (std::size_t f = 0; f < fine.size(); ++f) {
        const int J = fine[f];
        const int width = ap.ptr[J + 1] - ap.ptr[J];
        for (int k = 0; k < width; ++k) slot[ap.col[ap.ptr[J] + k]] = k;
        double* row = buffer.data() + start[f];
        const int a0 = A.outer[J * N], aw = A.outer[J * N + 1] - a0;
        for (int ka = 0; ka < aw; ka += N) {
          double a[N][N];
          for (int r = 0; r < N; ++r)
            for (int m = 0; m < N; ++m) a[r][m] = A.values[A.outer[J * N + r] + ka + m];
          const int M = A.inner[a0 + ka] / N;
          const int p0 = P.ptr[M * N], pw = P.ptr[M * N + 1] - p0;
          for (int kp = 0; kp < pw; kp += N) {
            double* blk = row + static_cast<std::size_t>(slot[P.idx[p0 + kp] / N]) * N * N;
            for (int r = 0; r < N; ++r)
              for (int c = 0; c < N; ++c) {
                double s = 0.0;
                for (int m = 0; m < N; ++m) s += a[r][m] * P.val[P.ptr[M * N + m] + kp + c];
                blk[r * N + c] += s;
              }
          }
        }
      }
      // C's rows: R's blocks in order, then A P's blocks of that row in order.
      for (int I = I0; I < I1; ++I) {
        const int c0 = C.ptr[I * N], cw = C.ptr[I * N + 1] - c0;
        double* crow[N];
        for (int r = 0; r < N; ++r) {
          crow[r] = C.val.data() + C.ptr[I * N + r];
          std::fill_n(crow[r], cw, 0.0);
        }
        for (int k = 0; k < cw; k += N) slot[C.idx[c0 + k] / N] = k;
        const int r0 = R.ptr[I * N], rw = R.ptr[I * N + 1] - r0;
        for (int kr = 0; kr < rw; kr += N) {
          double a[N][N];
          for (int r = 0; r < N; ++r)
            for (int m = 0; m < N; ++m) a[r][m] = R.val[R.ptr[I * N + r] + kr + m];
          const int J = R.idx[r0 + kr] / N;
          const double* row = buffer.data() + start[static_cast<std::size_t>(local[J])];
          for (int k = ap.ptr[J]; k < ap.ptr[J + 1]; ++k) {
            const int off = slot[ap.col[k]];
            const double* blk = row + static_cast<std::size_t>(k - ap.ptr[J]) * N * N;
            for (int r = 0; r < N; ++r)
              for (int c = 0; c < N; ++c) {
                double s = 0.0;
                for (int m = 0; m < N; ++m) s += a[r][m] * blk[m * N + c];
                crow[r][off + c] += s;
              }
          }
        }
      }
      for (const int J : fine) local[J] = -1;
    }
  }
}

}  // namespace

Csr galerkin(const Csr& R, const SparseView& A, const Csr& P, int block, NodePattern& ap, int threads) {
  Csr C;
  if (block == 3) {
    ap = node_pattern<3>(A, P, threads);
    C = galerkin_pattern<3>(R, ap, P.cols / 3, threads);
  } else {
    ap = node_pattern<2>(A, P, threads);
    C = galerkin_pattern<2>(R, ap, P.cols / 2, threads);
  }
  galerkin_values(R, A, P, ap, C, block, threads);
  return C;
}

void galerkin_values(const Csr& R, const SparseView& A, const Csr& P, const NodePattern& ap, Csr& C, int block,
                     int threads, int chunk) {
  if (block == 3) return galerkin_values_of<3>(R, A, P, ap, C, chunk, threads);
  galerkin_values_of<2>(R, A, P, ap, C, chunk, threads);
}

}  // namespace meshmorph::detail
