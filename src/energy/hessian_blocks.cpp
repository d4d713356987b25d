// SPDX-License-Identifier: MIT
// The node blocks and the diagonal of the Hessian that a HessianAction holds, without forming it.
#include <algorithm>
#include <array>
#include <utility>
#include <vector>

#include "energy/detail/hessian_kernels.h"
#include "energy/detail/node_gather.h"
#include "meshmorph/energy/assembler.h"
#include "meshmorph/error.h"
#include "meshmorph/threads.h"

namespace meshmorph {

template <int d>
std::vector<double> EnergyAssembler<d>::hessian_blocks(HessianAction<d>& action, int threads) const {
  constexpr int dd = detail::k_sq(d), pairs = detail::k_packed(d);
  MESHMORPH_CHECK(action.K_.size() == mesh_->cells.size(), "EnergyAssembler::hessian_blocks: the action does not fit");
  // Per cell and node the pairs (k, l), k ≤ l, of its block, packed by rows.
  std::vector<double>& local = action.local_;
  local.resize(static_cast<std::size_t>(pairs) * node_slots_.size());
  // S_jm^kl = K(k + dj, l + dm) + K(k + dm, l + dj) for j < m, K(k + dj, l + dj) for j = m:
  // the block (k, l) of node a is Σ_q Σ_{j ≤ m} ∂_j N_a ∂_m N_a S_jm^kl.
  const auto fields = [](std::pair<const float*, int> Kq, int j, int m, double* S) {
    const auto at = [&](int r, int c) {
      return double(Kq.first[Kq.second * (r <= c ? detail::packed_index(dd, r, c) : detail::packed_index(dd, c, r))]);
    };
    for (int k = 0, o = 0; k < d; ++k)
      for (int l = k; l < d; ++l, ++o) S[o] = at(k + d * j, l + d * m) + (j < m ? at(k + d * m, l + d * j) : 0.0);
  };
#pragma omp parallel num_threads(resolve_threads(threads))
  for (std::size_t bi = 0; bi < blocks_.size(); ++bi) {
    const CellBlock& block = mesh_->cells[bi];
    const ShapeTable& table = *targets_->blocks[bi].table;
    const int n = block.n_nodes_per_cell(), Q = table.n_points();
    const auto n_cells = static_cast<std::ptrdiff_t>(block.n_cells());
    const float* K = action.K_[bi].data();
    const std::vector<float>& E = action.element_[bi];
    double* out = local.data() + pairs * blocks_[bi].first_slot;
    const TensorGrid* t = action.tensor_[bi];
    // Sum factorization on hexahedra: ∂_j N_a ∂_m N_a at point q is a product of 1D tables,
    // l_i l_i, l_i l_i' or l_i' l_i' in each direction, so each field is contracted in three
    // 1D passes (O(m³P + m²P² + mP³) instead of O(m³P³)).
    std::array<Eigen::MatrixXd, 3> table1d;  // l l, l l', l' l' (m × P)
    if (t) table1d = {t->B.cwiseProduct(t->B), t->B.cwiseProduct(t->D), t->D.cwiseProduct(t->D)};
    std::vector<double> S, A, C;
    Eigen::Matrix<double, pairs, Eigen::Dynamic> h;
#pragma omp for schedule(static) nowait
    for (std::ptrdiff_t ci = 0; ci < n_cells; ++ci) {
      const auto c = static_cast<std::size_t>(ci);
      double* y = out + c * static_cast<std::size_t>(n * pairs);  // node a, pair o at pairs·a + o
      if (!E.empty()) {
        const int dn = d * n;
        const float* Ec = E.data() + c * static_cast<std::size_t>(detail::k_packed(dn));
        for (int a = 0; a < n; ++a)
          for (int k = 0, o = 0; k < d; ++k)
            for (int l = k; l < d; ++l, ++o) y[pairs * a + o] = Ec[detail::packed_index(dn, k * n + a, l * n + a)];
        continue;
      }
      const auto Kq = [&](int q) { return detail::point_entries<d>(K, t != nullptr, c, Q, q); };
      h.setZero(pairs, n);
      if (t) {
        if constexpr (d == 3) {
          const int P = t->basis->P, m = t->m;
          S.resize(static_cast<std::size_t>(pairs * Q));
          A.resize(static_cast<std::size_t>(pairs * m * m * P));
          C.resize(static_cast<std::size_t>(pairs * m * P * P));
          for (int j = 0; j < d; ++j)
            for (int mm = j; mm < d; ++mm) {
              for (int q = 0; q < Q; ++q) fields(Kq(q), j, mm, &S[static_cast<std::size_t>(pairs * q)]);
              const Eigen::MatrixXd& X = table1d[static_cast<std::size_t>((j == 0) + (mm == 0))];
              const Eigen::MatrixXd& Y = table1d[static_cast<std::size_t>((j == 1) + (mm == 1))];
              const Eigen::MatrixXd& Z = table1d[static_cast<std::size_t>((j == 2) + (mm == 2))];
              std::fill(A.begin(), A.end(), 0.0);  // A(qx, qy, iz)
              for (int qz = 0; qz < m; ++qz)
                for (int iz = 0; iz < P; ++iz) {
                  const double z = Z(qz, iz);
                  for (int qxy = 0; qxy < m * m; ++qxy)
                    for (int o = 0; o < pairs; ++o)
                      A[static_cast<std::size_t>(pairs * (qxy + m * m * iz) + o)] += z * S[static_cast<std::size_t>(pairs * (qxy + m * m * qz) + o)];
                }
              std::fill(C.begin(), C.end(), 0.0);  // C(qx, iy, iz)
              for (int iz = 0; iz < P; ++iz)
                for (int qy = 0; qy < m; ++qy)
                  for (int iy = 0; iy < P; ++iy) {
                    const double yv = Y(qy, iy);
                    for (int qx = 0; qx < m; ++qx)
                      for (int o = 0; o < pairs; ++o)
                        C[static_cast<std::size_t>(pairs * (qx + m * (iy + P * iz)) + o)] +=
                            yv * A[static_cast<std::size_t>(pairs * (qx + m * (qy + m * iz)) + o)];
                  }
              for (int iz = 0; iz < P; ++iz)
                for (int iy = 0; iy < P; ++iy)
                  for (int ix = 0; ix < P; ++ix) {
                    const int a = t->basis->node[static_cast<std::size_t>(ix + P * (iy + P * iz))];
                    for (int qx = 0; qx < m; ++qx) {
                      const double xv = X(qx, ix);
                      for (int o = 0; o < pairs; ++o) h(o, a) += xv * C[static_cast<std::size_t>(pairs * (qx + m * (iy + P * iz)) + o)];
                    }
                  }
            }
        }
      } else {
        double Sq[pairs];
        for (int q = 0; q < Q; ++q) {
          const double* dNq = table.dN.data() + static_cast<std::ptrdiff_t>(q) * d * n;  // column q·d + j at j·n
          for (int j = 0; j < d; ++j)
            for (int mm = j; mm < d; ++mm) {
              fields(Kq(q), j, mm, Sq);
              for (int a = 0; a < n; ++a) {
                const double w = dNq[j * n + a] * dNq[mm * n + a];
                for (int o = 0; o < pairs; ++o) h(o, a) += w * Sq[o];
              }
            }
        }
      }
      for (int a = 0; a < n; ++a)
        for (int o = 0; o < pairs; ++o) y[pairs * a + o] = h(o, a);
    }
  }
  std::vector<double> blocks(mesh_->n_nodes() * static_cast<std::size_t>(dd));
  std::array<std::array<int, 2>, pairs> pair;  // pair o = (k, l), packed by rows
  for (int k = 0, o = 0; k < d; ++k)
    for (int l = k; l < d; ++l, ++o) pair[static_cast<std::size_t>(o)] = {k, l};
  gather(local, pairs, threads, [&](std::ptrdiff_t i, int o, double sum) {
    const auto [k, l] = pair[static_cast<std::size_t>(o)];
    double* b = blocks.data() + static_cast<std::size_t>(i) * dd;
    b[k + d * l] = b[l + d * k] = sum;
  });
  return blocks;
}

template <int d>
Eigen::VectorXd EnergyAssembler<d>::hessian_diagonal(HessianAction<d>& action, int threads) const {
  const std::vector<double> blocks = hessian_blocks(action, threads);
  Eigen::VectorXd diagonal(static_cast<Eigen::Index>(dofs_->n_free()));
  const std::int32_t* red = dofs_->reduced_index().data();
  for (std::size_t i = 0; i < mesh_->n_nodes(); ++i)
    for (int k = 0; k < d; ++k)
      if (const std::int32_t r = red[d * i + k]; r >= 0) diagonal[r] = blocks[i * d * d + static_cast<std::size_t>(k * (d + 1))];
  return diagonal;
}

template std::vector<double> EnergyAssembler<2>::hessian_blocks(HessianAction<2>&, int) const;
template std::vector<double> EnergyAssembler<3>::hessian_blocks(HessianAction<3>&, int) const;
template Eigen::VectorXd EnergyAssembler<2>::hessian_diagonal(HessianAction<2>&, int) const;
template Eigen::VectorXd EnergyAssembler<3>::hessian_diagonal(HessianAction<3>&, int) const;

}  // namespace meshmorph
