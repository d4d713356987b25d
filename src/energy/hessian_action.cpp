// SPDX-License-Identifier: MIT
// Partial assembly of EnergyAssembler's Hessian: K_q per quadrature point, and its action.
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "energy/detail/element_kernel.h"
#include "energy/detail/hessian_kernels.h"
#include "energy/detail/node_gather.h"
#include "meshmorph/energy/assembler.h"
#include "meshmorph/error.h"
#include "meshmorph/fem/tensor_basis.h"
#include "meshmorph/threads.h"

namespace meshmorph {
namespace {

// Cells per dense product of apply_hessian: 16 cells give the products 3·16 rows in 3D, enough
// for the blocked kernel to amortise the packing of ∇N.
constexpr int k_batch = 16;

// The 1D factors of a hexahedral block whose table is a tensor grid (ShapeTable::tensor);
// null (dense products) elsewhere.
template <int d>
const TensorGrid* tensor_factors(const CellBlock& block, const ShapeTable& table) {
  return d == 3 && block.type == ElementType::Hexahedron ? table.tensor.get() : nullptr;
}

}  // namespace

template <int d>
bool EnergyAssembler<d>::prepare_hessian(const Metric<d>& metric, const Eigen::MatrixXd& x, HessianMode mode, int threads,
                                         HessianAction<d>& out) const {
  constexpr int dd = detail::k_sq(d);
  using Hess = Eigen::Matrix<double, dd, dd>;
  out.K_.resize(mesh_->cells.size());
  out.element_.resize(mesh_->cells.size());
  out.tensor_.clear();
  for (std::size_t bi = 0; bi < mesh_->cells.size(); ++bi)
    out.tensor_.push_back(tensor_factors<d>(mesh_->cells[bi], *targets_->blocks[bi].table));
  int finite = 1;
  for (std::size_t bi = 0; bi < mesh_->cells.size(); ++bi) {
    const CellBlock& block = mesh_->cells[bi];
    const BlockTargets<d>& bt = targets_->blocks[bi];
    const ShapeTable& table = *bt.table;
    const int n = block.n_nodes_per_cell(), Q = bt.n_points();
    std::vector<float>& K = out.K_[bi];
    std::vector<float>& E = out.element_[bi];
    const auto n_cells = static_cast<std::ptrdiff_t>(block.n_cells());
    if (is_simplex(block.type)) {
      // Element matrices (component-major, as detail::element_kernel): on simplices (d·n)² is
      // less than the per-point data and its products, e.g. 3600 against 46·45 + 2·3·20·138 for
      // a P3 tetrahedron at degree 8.
      K.clear();
      const int dn = d * n;
      E.resize(block.n_cells() * static_cast<std::size_t>(detail::k_packed(dn)));
#pragma omp parallel for num_threads(resolve_threads(threads)) schedule(static) reduction(&& : finite)
      for (std::ptrdiff_t c = 0; c < n_cells; ++c) {
        detail::NodalMatrix<d> X(d, n);
        detail::ElementScratch<d> scratch;
        const std::int32_t* nodes = block.cell(static_cast<std::size_t>(c));
        for (int a = 0; a < n; ++a) X.col(a) = x.col(nodes[a]);
        const double e = detail::element_kernel<d>(metric, table, bt.cell(static_cast<std::size_t>(c)), X, Want::Hessian, mode, scratch);
        if (!(e < std::numeric_limits<double>::infinity())) {
          finite = 0;
          continue;
        }
        float* packed = E.data() + static_cast<std::size_t>(c) * detail::k_packed(dn);
        for (int i = 0; i < dn; ++i)
          for (int j = i; j < dn; ++j) *packed++ = static_cast<float>(scratch.H(i, j));  // exactly symmetric (complete_symmetric)
      }
      continue;
    }
    E.clear();
    // Cells in batches of k_lanes, interleaved, where hex_kernel takes them (detail/hessian_kernels.h).
    const bool lanes = out.tensor_[bi] != nullptr;
    const std::size_t padded = lanes ? (block.n_cells() + detail::k_lanes - 1) / detail::k_lanes * detail::k_lanes : block.n_cells();
    K.assign(padded * static_cast<std::size_t>(Q) * detail::k_packed(dd), 0.0f);
    const TensorGrid* grid = table.tensor && table.dim == d ? table.tensor.get() : nullptr;
#pragma omp parallel num_threads(resolve_threads(threads)) reduction(&& : finite)
    {
      Eigen::MatrixXd Gs(d, d * Q);  // G_q in column block q, one buffer a thread
#pragma omp for schedule(static)
      for (std::ptrdiff_t c = 0; c < n_cells; ++c) {
        detail::NodalMatrix<d> X(d, n);
        const std::int32_t* nodes = block.cell(static_cast<std::size_t>(c));
        for (int a = 0; a < n; ++a) X.col(a) = x.col(nodes[a]);
        const QuadratureTarget<d>* t = bt.cell(static_cast<std::size_t>(c));
        // The reference gradients at all points, by sum factorization where the table allows,
        // and T as element_kernel forms it.
        if (grid)
          grid_gradients(*grid, X.data(), d, Gs.data());
        else
          for (int q = 0; q < Q; ++q) Gs.middleCols(q * d, d).noalias() = X.lazyProduct(table.grad(q));
        for (int q = 0; q < Q; ++q) {
          const MatT<d> T = Eigen::Map<const MatT<d>>(Gs.data() + d * d * q).lazyProduct(t[q].W_inv);
          const MetricEval<d> ev = metric.eval(T, Want::Hessian);
          if (!(ev.mu < std::numeric_limits<double>::infinity())) {
            finite = 0;
            continue;
          }
          Hess Hq = ev.d2mu_dT2;
          if (mode == HessianMode::Projected) detail::project_isotropic<d>(T, Hq);
          // M = W⁻¹ ⊗ I: M(k + dj, k + dm) = W⁻¹(j, m), so that vec(T) = Mᵀ vec(G). Ideal
          // targets of tensor cells have W⁻¹ = s I, where M Hq Mᵀ = s² Hq.
          const MatT<d>& W_inv = t[q].W_inv;
          Hess Kq;
          if (W_inv.isDiagonal(0.0) && (W_inv.diagonal().array() == W_inv(0, 0)).all()) {
            Kq = (t[q].weight * W_inv(0, 0) * W_inv(0, 0)) * Hq;
          } else {
            Hess M = Hess::Zero();
            for (int j = 0; j < d; ++j)
              for (int m = 0; m < d; ++m)
                for (int k = 0; k < d; ++k) M(k + d * j, k + d * m) = W_inv(j, m);
            Kq = t[q].weight * (M * Hq * M.transpose());
          }
          const auto [packed, stride] = detail::point_entries<d>(K.data(), lanes, static_cast<std::size_t>(c), Q, q);
          for (int i = 0, e = 0; i < dd; ++i)
            for (int j = i; j < dd; ++j, ++e) packed[e * stride] = static_cast<float>(0.5 * (Kq(i, j) + Kq(j, i)));
        }
      }
    }
  }
  return finite != 0;
}

template <int d>
void EnergyAssembler<d>::apply_hessian(HessianAction<d>& action, const Eigen::VectorXd& v, Eigen::VectorXd& y,
                                       int threads) const {
  constexpr int dd = detail::k_sq(d);
  MESHMORPH_CHECK(action.K_.size() == mesh_->cells.size() && v.size() == static_cast<Eigen::Index>(dofs_->n_free()),
                  "EnergyAssembler::apply_hessian: the action or v does not fit");
  std::vector<double>& local = action.local_;
  local.resize(static_cast<std::size_t>(d) * node_slots_.size());
  const std::int32_t* red = dofs_->reduced_index().data();
#pragma omp parallel num_threads(resolve_threads(threads))
  {
    Eigen::MatrixXd V, R, Y;
    Eigen::VectorXd ue, ye;
    detail::HexScratch hex;
    for (std::size_t bi = 0; bi < blocks_.size(); ++bi) {
      const CellBlock& block = mesh_->cells[bi];
      const Eigen::MatrixXd& dN = targets_->blocks[bi].table->dN;  // n × dQ
      const int n = block.n_nodes_per_cell(), Q = targets_->blocks[bi].n_points();
      const auto n_cells = static_cast<std::ptrdiff_t>(block.n_cells());
      const float* K = action.K_[bi].data();
      const auto K_of = [&](std::size_t c) { return K + c * static_cast<std::size_t>(Q) * detail::k_packed(dd); };
      // y_e of cell c, node a, component k.
      double* out = local.data() + d * blocks_[bi].first_slot;
      const auto y_of = [&](std::size_t c, int a, int k) -> double& { return out[(c * n + static_cast<std::size_t>(a)) * d + k]; };
      if constexpr (d == 3) {
        if (const TensorGrid* t = action.tensor_[bi]) {
          const std::vector<std::int32_t>& lattice_node = t->basis->node;
          const std::ptrdiff_t n_batches = (n_cells + detail::k_lanes - 1) / detail::k_lanes;
#pragma omp for schedule(static) nowait
          for (std::ptrdiff_t batch = 0; batch < n_batches; ++batch) {
            const int lanes = static_cast<int>(std::min<std::ptrdiff_t>(detail::k_lanes, n_cells - batch * detail::k_lanes));
            hex.u.assign(static_cast<std::size_t>(3 * detail::k_lanes * n), 0.0);
            for (int e = 0; e < lanes; ++e) {
              const std::int32_t* nodes = block.cell(static_cast<std::size_t>(batch * detail::k_lanes + e));
              for (int l = 0; l < n; ++l)
                for (int k = 0; k < 3; ++k)
                  if (const std::int32_t r = red[3 * nodes[lattice_node[static_cast<std::size_t>(l)]] + k]; r >= 0)
                    hex.u[static_cast<std::size_t>((3 * l + k) * detail::k_lanes + e)] = v[r];
            }
            detail::hex_kernel(*t, K + static_cast<std::size_t>(batch) * Q * detail::k_packed(dd) * detail::k_lanes, hex);
            for (int e = 0; e < lanes; ++e) {
              const auto c = static_cast<std::size_t>(batch * detail::k_lanes + e);
              for (int l = 0; l < n; ++l)
                for (int k = 0; k < 3; ++k)
                  y_of(c, lattice_node[static_cast<std::size_t>(l)], k) =
                      hex.y[static_cast<std::size_t>((3 * l + k) * detail::k_lanes + e)];
            }
          }
          continue;
        }
      }
      if (const std::vector<float>& E = action.element_[bi]; !E.empty()) {
        const int dn = d * n;
        ue.resize(dn);
        ye.resize(dn);
#pragma omp for schedule(static) nowait
        for (std::ptrdiff_t ci = 0; ci < n_cells; ++ci) {
          const auto c = static_cast<std::size_t>(ci);
          const std::int32_t* nodes = block.cell(c);
          for (int a = 0; a < n; ++a)
            for (int k = 0; k < d; ++k) {
              const std::int32_t r = red[d * nodes[a] + k];
              ue[k * n + a] = r >= 0 ? v[r] : 0.0;
            }
          detail::packed_product(E.data() + c * static_cast<std::size_t>(detail::k_packed(dn)), ue.data(), ye.data(), dn);
          for (int a = 0; a < n; ++a)
            for (int k = 0; k < d; ++k) y_of(c, a, k) = ye[k * n + a];
        }
        continue;
      }
      // Dense: k_batch cells at a time, their nodal values stacked as the d·b rows of V, so
      // that one product R = V ∇N over all points (the reference gradients G_q of cell e in
      // rows d·e .. d·e + d − 1, column block q) and one back share the packing of ∇N; K_q
      // applied per cell and point in between.
      const std::ptrdiff_t n_batches = (n_cells + k_batch - 1) / k_batch;
#pragma omp for schedule(static) nowait
      for (std::ptrdiff_t batch = 0; batch < n_batches; ++batch) {
        const std::size_t first = static_cast<std::size_t>(batch) * k_batch;
        const int b = static_cast<int>(std::min<std::ptrdiff_t>(k_batch, n_cells - batch * k_batch));
        V.resize(d * b, n);
        for (int e = 0; e < b; ++e) {
          const std::int32_t* nodes = block.cell(first + static_cast<std::size_t>(e));
          for (int a = 0; a < n; ++a)
            for (int k = 0; k < d; ++k) {
              const std::int32_t r = red[d * nodes[a] + k];
              V(d * e + k, a) = r >= 0 ? v[r] : 0.0;
            }
        }
        R.noalias() = V * dN;
        for (int e = 0; e < b; ++e) {
          const float* Kc = K_of(first + static_cast<std::size_t>(e));
          for (int q = 0; q < Q; ++q) {
            Eigen::Matrix<double, dd, 1> g;
            for (int j = 0; j < d; ++j)
              for (int k = 0; k < d; ++k) g[k + d * j] = R(d * e + k, q * d + j);
            Eigen::Matrix<double, dd, 1> h;
            detail::packed_product<dd>(Kc + q * detail::k_packed(dd), g.data(), h.data());
            for (int j = 0; j < d; ++j)
              for (int k = 0; k < d; ++k) R(d * e + k, q * d + j) = h[k + d * j];
          }
        }
        Y.noalias() = R * dN.transpose();
        for (int e = 0; e < b; ++e)
          for (int a = 0; a < n; ++a)
            for (int k = 0; k < d; ++k) y_of(first + static_cast<std::size_t>(e), a, k) = Y(d * e + k, a);
      }
    }
  }
  y.setZero(static_cast<Eigen::Index>(dofs_->n_free()));
  gather(local, d, threads, [&](std::ptrdiff_t i, int k, double sum) {
    if (const std::int32_t r = red[d * i + k]; r >= 0) y[r] = sum;
  });
}

template bool EnergyAssembler<2>::prepare_hessian(const Metric<2>&, const Eigen::MatrixXd&, HessianMode, int,
                                                  HessianAction<2>&) const;
template bool EnergyAssembler<3>::prepare_hessian(const Metric<3>&, const Eigen::MatrixXd&, HessianMode, int,
                                                  HessianAction<3>&) const;
template void EnergyAssembler<2>::apply_hessian(HessianAction<2>&, const Eigen::VectorXd&, Eigen::VectorXd&, int) const;
template void EnergyAssembler<3>::apply_hessian(HessianAction<3>&, const Eigen::VectorXd&, Eigen::VectorXd&, int) const;

}  // namespace meshmorph
