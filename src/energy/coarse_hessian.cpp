// SPDX-License-Identifier: MIT
// The Galerkin coarse matrix Rᵀ H R of the Hessian that a HessianAction holds, cell by cell.
#include <algorithm>
#include <array>
#include <vector>

#include "energy/detail/hessian_kernels.h"
#include "meshmorph/energy/assembler.h"
#include "meshmorph/threads.h"

namespace meshmorph {
namespace {

// Ac += Σ_q G_q K_q^{kl} G_qᵀ over the pairs k ≤ l of the cell's points (the blocks (k, l)
// of the local coarse matrix, corners × corners, v·d + k order), from the hats' gradients G_q
// (C × d) and the packed K_q; C fixed at compile time (8: hexahedra) or at run time (0).
template <int d, int C_>
void coarse_points(const std::vector<Eigen::MatrixXd>& gradients, int corners, const float* K, bool lanes, std::size_t c,
                   int Q, Eigen::MatrixXd& Ac) {
  constexpr int dd = detail::k_sq(d);
  constexpr int C = C_ > 0 ? C_ : Eigen::Dynamic;
  constexpr int max_c = C_ > 0 ? C_ : 8;  // hexahedra have the most corners
  using Grad = Eigen::Matrix<double, C, d, Eigen::ColMajor, max_c, d>;
  using Block = Eigen::Matrix<double, C, C, Eigen::ColMajor, max_c, max_c>;
  std::array<Block, detail::k_packed(d)> blocks;
  for (Block& b : blocks) b.setZero(corners, corners);
  for (int q = 0; q < Q; ++q) {
    // Not a structured binding: clang before 16 cannot capture one in a lambda.
    const auto entries = detail::point_entries<d>(K, lanes, c, Q, q);
    const auto entry = entries.first;
    const int stride = entries.second;
    const auto Kq = [&](int i, int j) {  // K_q(i, j) from the packed upper triangle
      return static_cast<double>(entry[(i <= j ? detail::packed_index(dd, i, j) : detail::packed_index(dd, j, i)) * stride]);
    };
    const Grad G = gradients[static_cast<std::size_t>(q)];
    for (int k = 0, o = 0; k < d; ++k)
      for (int l = k; l < d; ++l, ++o) {
        Eigen::Matrix<double, d, d> Kkl;  // (j, m) ↦ K_q(k + d j, l + d m)
        for (int j = 0; j < d; ++j)
          for (int m = 0; m < d; ++m) Kkl(j, m) = Kq(k + d * j, l + d * m);
        const Grad GK = G.lazyProduct(Kkl);
        blocks[static_cast<std::size_t>(o)].noalias() += GK.lazyProduct(G.transpose());
      }
  }
  for (int k = 0, o = 0; k < d; ++k)
    for (int l = k; l < d; ++l, ++o)
      for (int v = 0; v < corners; ++v)
        for (int w = 0; w < corners; ++w) {
          Ac(v * d + k, w * d + l) = blocks[static_cast<std::size_t>(o)](v, w);
          Ac(w * d + l, v * d + k) = blocks[static_cast<std::size_t>(o)](v, w);
        }
}

}  // namespace

template <int d>
Eigen::SparseMatrix<double> EnergyAssembler<d>::coarse_hessian(const HessianAction<d>& action, const CoarseSpace<d>& coarse,
                                                               int threads) const {
  Eigen::SparseMatrix<double> A = coarse.pattern();
  double* values = A.valuePtr();
  for (std::size_t bi = 0; bi < blocks_.size(); ++bi) {
    const CellBlock& block = mesh_->cells[bi];
    const typename CoarseSpace<d>::Block& cb = coarse.block(bi);
    const int n = block.n_nodes_per_cell(), Q = targets_->blocks[bi].n_points(), m = d * cb.corners;
    const auto n_cells = static_cast<std::ptrdiff_t>(block.n_cells());
    const std::vector<float>& E = action.element_[bi];
    const float* K = action.K_[bi].data();
    const bool lanes = action.tensor_[bi] != nullptr;
    // The cells' coarse matrices (local coarse DOF v·d + k), then added in cell order.
    std::vector<double> local(static_cast<std::size_t>(n_cells) * m * m);
#pragma omp parallel num_threads(resolve_threads(threads))
    {
      Eigen::MatrixXd Ac(m, m), Ed, T;
#pragma omp for schedule(static)
      for (std::ptrdiff_t ci = 0; ci < n_cells; ++ci) {
        const auto c = static_cast<std::size_t>(ci);
        if (!E.empty()) {
          // R_eᵀ H_e R_e with H_e component-major (k·n + a) and R_e the hats at the nodes.
          const int dn = d * n;
          Ed.resize(dn, dn);
          const float* packed = E.data() + c * static_cast<std::size_t>(detail::k_packed(dn));
          for (int i = 0; i < dn; ++i)
            for (int j = i; j < dn; ++j) Ed(i, j) = Ed(j, i) = *packed++;
          for (int l = 0; l < d; ++l) {
            T.noalias() = Ed.middleCols(l * n, n) * cb.values;  // dn × corners
            for (int k = 0; k < d; ++k) {
              const Eigen::MatrixXd Akl = cb.values.transpose() * T.middleRows(k * n, n);
              for (int v = 0; v < cb.corners; ++v)
                for (int w = 0; w < cb.corners; ++w) Ac(v * d + k, w * d + l) = Akl(v, w);
            }
          }
          Ac = 0.5 * (Ac + Ac.transpose()).eval();
        } else if (d == 3 && cb.corners == 8) {
          coarse_points<d, 8>(cb.gradients, cb.corners, K, lanes, c, Q, Ac);
        } else {
          coarse_points<d, 0>(cb.gradients, cb.corners, K, lanes, c, Q, Ac);
        }
        std::copy(Ac.data(), Ac.data() + m * m, local.data() + c * static_cast<std::size_t>(m * m));
      }
    }
    for (std::size_t c = 0; c < static_cast<std::size_t>(n_cells); ++c) {
      const double* a = local.data() + c * static_cast<std::size_t>(m * m);
      const std::int32_t* off = coarse.scatter(bi, c);
      for (int i = 0; i < m * m; ++i)
        if (off[i] >= 0) values[off[i]] += a[i];
    }
  }
  return A;
}

template Eigen::SparseMatrix<double> EnergyAssembler<2>::coarse_hessian(const HessianAction<2>&, const CoarseSpace<2>&, int) const;
template Eigen::SparseMatrix<double> EnergyAssembler<3>::coarse_hessian(const HessianAction<3>&, const CoarseSpace<3>&, int) const;

}  // namespace meshmorph
