// SPDX-License-Identifier: MIT
#pragma once
#include <cstddef>
#include <utility>
#include <vector>

#include "meshmorph/fem/tensor_basis.h"

namespace meshmorph::detail {

/// d², the size of vec(G) for a d × d reference gradient G.
constexpr int k_sq(int d) { return d * d; }
/// Entries of a symmetric dd × dd matrix packed by rows of its upper triangle: how
/// HessianAction stores K_q (d²(d² + 1)/2 floats a point) and the element Hessians
/// (component-major local order k·n + a, d·n(d·n + 1)/2 floats a cell).
constexpr int k_packed(int dd) { return dd * (dd + 1) / 2; }
/// Entry (i, j), i ≤ j, of a packed dd × dd matrix.
constexpr int packed_index(int dd, int i, int j) { return i * dd - i * (i - 1) / 2 + (j - i); }

/// Cells per batch of the sum-factorized product (one SIMD lane each). A sum-factorized
/// block's K_q are stored by batch × point × packed entry × lane, the last batch padded with
/// zeros; other blocks' by cell × point × packed entry.
constexpr int k_lanes = 4;

/// h = K g for K packed as k_packed(dd): K is read once, which bounds a matrix-free product
/// (the K of every point are the bulk of its memory traffic).
template <int dd>
inline void packed_product(const float* K, const double* g, double* h) {
  for (int i = 0; i < dd; ++i) h[i] = 0.0;
  for (int i = 0, o = 0; i < dd; ++i) {
    h[i] += double(K[o++]) * g[i];
    for (int j = i + 1; j < dd; ++j, ++o) {
      const double k = K[o];
      h[i] += k * g[j];
      h[j] += k * g[i];
    }
  }
}

/// h = K g for a packed symmetric n × n K (as packed_product<dd>, n at run time).
inline void packed_product(const float* K, const double* g, double* h, int n) {
  for (int i = 0; i < n; ++i) h[i] = 0.0;
  for (int i = 0; i < n; ++i) {
    const double gi = g[i];
    double hi = h[i] + double(K[0]) * gi;
    for (int j = i + 1; j < n; ++j) {
      const double k = K[j - i];
      hi += k * g[j];
      h[j] += k * gi;
    }
    h[i] = hi;
    K += n - i;
  }
}

/// The packed K_q of cell c at point q (of Q) in a block's K: its first entry and the stride
/// between entries (k_lanes where the cells are interleaved by lanes, else 1).
template <int d, class T>
std::pair<T*, int> point_entries(T* K, bool lanes, std::size_t c, int Q, int q) {
  constexpr auto n = static_cast<std::size_t>(k_packed(d * d));
  if (!lanes) return {K + (c * static_cast<std::size_t>(Q) + static_cast<std::size_t>(q)) * n, 1};
  const std::size_t batch = c / k_lanes, lane = c % k_lanes;
  return {K + ((batch * static_cast<std::size_t>(Q) + static_cast<std::size_t>(q)) * n) * k_lanes + lane, k_lanes};
}

/// Work space of hex_kernel: u, y and the 1D passes' fields, each entry k_lanes wide.
struct HexScratch {
  std::vector<double> u, y, A0, A1, C00, C01, C10, E00, E01, E10, F0, F1;
};

/// y_e = Σ_q mat(K_q vec(G_q)) ∇N_qᵀ on k_lanes hexahedra at once by sum factorization
/// (G_q = U_e ∇N_q, three components): from the nodal values U_e in s.u into s.y, both in
/// lattice order (TensorBasis::node), then component, then lane; K the batch's K_q (point,
/// packed entry, lane). O(m P³ + m² P² + m³ P) per component instead of O(m³ P³).
void hex_kernel(const TensorGrid& t, const float* K, HexScratch& s);

}  // namespace meshmorph::detail
