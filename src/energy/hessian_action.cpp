// SPDX-License-Identifier: MIT
// Partial assembly of EnergyAssembler's Hessian: K_q per quadrature point, and its action.
#include <limits>

#include <omp.h>

#include "energy/detail/element_kernel.h"
#include "meshmorph/energy/assembler.h"
#include "meshmorph/error.h"

namespace meshmorph {
namespace {

constexpr int k_sq(int d) { return d * d; }

int threads_of(int requested) { return requested > 0 ? requested : omp_get_max_threads(); }

}  // namespace

template <int d>
bool EnergyAssembler<d>::prepare_hessian(const Metric<d>& metric, const Eigen::MatrixXd& x, HessianMode mode, int threads,
                                         HessianAction<d>& out) const {
  constexpr int dd = k_sq(d);
  using Hess = Eigen::Matrix<double, dd, dd>;
  out.K.resize(mesh_->cells.size());
  int finite = 1;
  for (std::size_t bi = 0; bi < mesh_->cells.size(); ++bi) {
    const CellBlock& block = mesh_->cells[bi];
    const BlockTargets<d>& bt = targets_->blocks[bi];
    const ShapeTable& table = *bt.table;
    const int n = block.n_nodes_per_cell(), Q = bt.n_points();
    std::vector<double>& K = out.K[bi];
    K.resize(block.n_cells() * static_cast<std::size_t>(Q) * dd * dd);
    const auto n_cells = static_cast<std::ptrdiff_t>(block.n_cells());
#pragma omp parallel for num_threads(threads_of(threads)) schedule(static) reduction(&& : finite)
    for (std::ptrdiff_t c = 0; c < n_cells; ++c) {
      detail::NodalMatrix<d> X(d, n);
      const std::int32_t* nodes = block.cell(static_cast<std::size_t>(c));
      for (int a = 0; a < n; ++a) X.col(a) = x.col(nodes[a]);
      const QuadratureTarget<d>* t = bt.cell(static_cast<std::size_t>(c));
      for (int q = 0; q < Q; ++q) {
        const MatT<d> G = X.lazyProduct(table.grad(q));
        const MatT<d> T = G * t[q].W_inv;
        const MetricEval<d> ev = metric.eval(T, Want::Hessian);
        if (!(ev.mu < std::numeric_limits<double>::infinity())) {
          finite = 0;
          continue;
        }
        Hess Hq = ev.d2mu_dT2;
        if (mode == HessianMode::Projected) detail::project_isotropic<d>(T, Hq);
        // M = W⁻¹ ⊗ I: M(k + dj, k + dm) = W⁻¹(j, m), so that vec(T) = Mᵀ vec(G).
        Hess M = Hess::Zero();
        for (int j = 0; j < d; ++j)
          for (int m = 0; m < d; ++m)
            for (int k = 0; k < d; ++k) M(k + d * j, k + d * m) = t[q].W_inv(j, m);
        Eigen::Map<Hess>(K.data() + (static_cast<std::size_t>(c) * Q + q) * dd * dd).noalias() =
            t[q].weight * (M * Hq * M.transpose());
      }
    }
  }
  return finite != 0;
}

template <int d>
void EnergyAssembler<d>::apply_hessian(const HessianAction<d>& action, const Eigen::VectorXd& v, Eigen::VectorXd& y,
                                       int threads) const {
  constexpr int dd = k_sq(d);
  MESHMORPH_CHECK(action.K.size() == mesh_->cells.size() && v.size() == static_cast<Eigen::Index>(dofs_->n_free()),
                  "EnergyAssembler::apply_hessian: the action or v does not fit");
  y.setZero(v.size());
  const std::int32_t* red = dofs_->reduced_index().data();
#pragma omp parallel num_threads(threads_of(threads))
  {
    Eigen::Matrix<double, d, Eigen::Dynamic> V, R, Y;
    for (std::size_t bi = 0; bi < blocks_.size(); ++bi) {
      const CellBlock& block = mesh_->cells[bi];
      const Eigen::MatrixXd& dN = targets_->blocks[bi].table->dN;  // n × dQ
      const BlockPlan& plan = blocks_[bi];
      const int n = block.n_nodes_per_cell(), Q = targets_->blocks[bi].n_points();
      const double* K = action.K[bi].data();
      V.resize(d, n);
      // Patches of one colour share no node (assemble()): their scatters never collide.
      for (std::size_t color = 0; color + 1 < plan.color_offset.size(); ++color) {
#pragma omp for schedule(dynamic, 1)
        for (std::int32_t p = plan.color_offset[color]; p < plan.color_offset[color + 1]; ++p)
          for (std::int32_t i = plan.patch_offset[p]; i < plan.patch_offset[p + 1]; ++i) {
            const auto c = static_cast<std::size_t>(plan.order[static_cast<std::size_t>(i)]);
            const std::int32_t* nodes = block.cell(c);
            for (int a = 0; a < n; ++a)
              for (int k = 0; k < d; ++k) {
                const std::int32_t r = red[d * nodes[a] + k];
                V(k, a) = r >= 0 ? v[r] : 0.0;
              }
            // One product over all points for the reference gradients G_q = V ∇N_q (the
            // column blocks of R), K_q applied in place, one product back.
            R.noalias() = V * dN;
            const double* Kc = K + c * static_cast<std::size_t>(Q) * dd * dd;
            for (int q = 0; q < Q; ++q) {
              Eigen::Map<Eigen::Matrix<double, dd, 1>> g(R.data() + q * dd);
              const Eigen::Matrix<double, dd, 1> s = Eigen::Map<const Eigen::Matrix<double, dd, dd>>(Kc + q * dd * dd) * g;
              g = s;
            }
            Y.noalias() = R * dN.transpose();
            for (int a = 0; a < n; ++a)
              for (int k = 0; k < d; ++k)
                if (const std::int32_t r = red[d * nodes[a] + k]; r >= 0) y[r] += Y(k, a);
          }
      }
    }
  }
}

template <int d>
Eigen::VectorXd EnergyAssembler<d>::hessian_diagonal(const HessianAction<d>& action, int threads) const {
  constexpr int dd = k_sq(d);
  MESHMORPH_CHECK(action.K.size() == mesh_->cells.size(), "EnergyAssembler::hessian_diagonal: the action does not fit");
  Eigen::VectorXd diagonal = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(dofs_->n_free()));
  const std::int32_t* red = dofs_->reduced_index().data();
#pragma omp parallel num_threads(threads_of(threads))
  for (std::size_t bi = 0; bi < blocks_.size(); ++bi) {
    const CellBlock& block = mesh_->cells[bi];
    const ShapeTable& table = *targets_->blocks[bi].table;
    const BlockPlan& plan = blocks_[bi];
    const int n = block.n_nodes_per_cell(), Q = table.n_points();
    const double* K = action.K[bi].data();
    for (std::size_t color = 0; color + 1 < plan.color_offset.size(); ++color) {
#pragma omp for schedule(dynamic, 1)
      for (std::int32_t p = plan.color_offset[color]; p < plan.color_offset[color + 1]; ++p)
        for (std::int32_t i = plan.patch_offset[p]; i < plan.patch_offset[p + 1]; ++i) {
          const auto c = static_cast<std::size_t>(plan.order[static_cast<std::size_t>(i)]);
          const std::int32_t* nodes = block.cell(c);
          const double* Kc = K + c * static_cast<std::size_t>(Q) * dd * dd;
          for (int a = 0; a < n; ++a) {
            Eigen::Matrix<double, d, 1> h = Eigen::Matrix<double, d, 1>::Zero();
            for (int q = 0; q < Q; ++q) {
              const Eigen::Map<const Eigen::Matrix<double, dd, dd>> Kq(Kc + q * dd * dd);
              for (int j = 0; j < d; ++j)
                for (int m = 0; m < d; ++m) {
                  const double w = table.dN(a, q * d + j) * table.dN(a, q * d + m);
                  for (int k = 0; k < d; ++k) h[k] += w * Kq(k + d * j, k + d * m);
                }
            }
            for (int k = 0; k < d; ++k)
              if (const std::int32_t r = red[d * nodes[a] + k]; r >= 0) diagonal[r] += h[k];
          }
        }
    }
  }
  return diagonal;
}

template class EnergyAssembler<2>;
template class EnergyAssembler<3>;

}  // namespace meshmorph
