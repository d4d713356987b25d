// SPDX-License-Identifier: MIT
#include <algorithm>
#include <cmath>
#include <numeric>

#include "solve/detail/amg.h"

namespace meshmorph::detail {
namespace {

// The strong-neighbour graph of the nodes (CSR, without the node itself).
struct Graph {
  std::vector<int> ptr, idx;
};

Graph strong_graph(const SparseView& A, int block, double theta, int threads) {
  const int n_nodes = A.n / block;
  std::vector<double> self(static_cast<std::size_t>(n_nodes), 0.0);  // ‖A_II‖_F
#pragma omp parallel for num_threads(threads) schedule(static)
  for (int I = 0; I < n_nodes; ++I) {
    double s = 0.0;
    for (int i = I * block; i < (I + 1) * block; ++i)
      for (int k = A.outer[i]; k < A.outer[i + 1]; ++k)
        if (A.inner[k] / block == I) s += A.values[k] * A.values[k];
    self[I] = std::sqrt(s);
  }
  const double theta2 = theta * theta;
  Graph g;
  g.ptr.assign(static_cast<std::size_t>(n_nodes) + 1, 0);
  // Two passes over the same loop: count the strong neighbours, then write them.
  for (int pass = 0; pass < 2; ++pass) {
    if (pass == 1) {
      std::partial_sum(g.ptr.begin(), g.ptr.end(), g.ptr.begin());
      g.idx.resize(static_cast<std::size_t>(g.ptr.back()));
    }
#pragma omp parallel num_threads(threads)
    {
      std::vector<double> sum(static_cast<std::size_t>(n_nodes), 0.0);
      std::vector<int> touched;
#pragma omp for schedule(dynamic, 256)
      for (int I = 0; I < n_nodes; ++I) {
        touched.clear();
        for (int i = I * block; i < (I + 1) * block; ++i)
          for (int k = A.outer[i]; k < A.outer[i + 1]; ++k) {
            const int J = A.inner[k] / block;
            if (J == I) continue;
            if (sum[J] == 0.0) touched.push_back(J);
            sum[J] += A.values[k] * A.values[k] + 1e-300;  // keeps a structural zero "touched"
          }
        int c = 0;
        int out = pass == 1 ? g.ptr[I] : 0;
        std::sort(touched.begin(), touched.end());
        for (int J : touched) {
          if (sum[J] >= theta2 * self[I] * self[J]) {
            if (pass == 1) g.idx[out++] = J;
            ++c;
          }
          sum[J] = 0.0;
        }
        if (pass == 0) g.ptr[I + 1] = c;
      }
    }
  }
  return g;
}

}  // namespace

std::vector<int> aggregate_nodes(const SparseView& A, int block, double theta, int threads, int& n_aggregates) {
  const Graph g = strong_graph(A, block, theta, threads);
  const int n_nodes = A.n / block;
  std::vector<int> agg(static_cast<std::size_t>(n_nodes), -1);
  int n = 0;
  // Pass 1: a node whose strong neighbours are all free starts an aggregate with them.
  for (int I = 0; I < n_nodes; ++I) {
    if (agg[I] >= 0) continue;
    bool free = true;
    for (int k = g.ptr[I]; k < g.ptr[I + 1] && free; ++k) free = agg[g.idx[k]] < 0;
    if (!free) continue;
    agg[I] = n;
    for (int k = g.ptr[I]; k < g.ptr[I + 1]; ++k) agg[g.idx[k]] = n;
    ++n;
  }
  // Pass 2: a leftover joins the aggregate of its first strong neighbour from pass 1.
  std::vector<int> joined = agg;
  for (int I = 0; I < n_nodes; ++I) {
    if (agg[I] >= 0) continue;
    for (int k = g.ptr[I]; k < g.ptr[I + 1]; ++k)
      if (agg[g.idx[k]] >= 0) {
        joined[I] = agg[g.idx[k]];
        break;
      }
  }
  agg = std::move(joined);
  // Pass 3: what is left (only reachable through leftovers) forms aggregates of its own.
  for (int I = 0; I < n_nodes; ++I) {
    if (agg[I] >= 0) continue;
    agg[I] = n;
    for (int k = g.ptr[I]; k < g.ptr[I + 1]; ++k)
      if (agg[g.idx[k]] < 0) agg[g.idx[k]] = n;
    ++n;
  }
  n_aggregates = n;
  return agg;
}

}  // namespace meshmorph::detail
