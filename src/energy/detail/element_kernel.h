// SPDX-License-Identifier: MIT
#pragma once
#include <limits>

#include <Eigen/Core>

#include "meshmorph/energy/element_energy.h"
#include "energy/detail/isotropic_projection.h"
#include "meshmorph/fem/tensor_basis.h"

namespace meshmorph::detail {

/// Largest node count of an element the kernel accepts (hexahedron of order 4).
inline constexpr int k_max_nodes = 125;

template <int d>
using NodalMatrix = Eigen::Matrix<double, d, Eigen::Dynamic, Eigen::ColMajor, d, k_max_nodes>;

/// Per-thread work space of the element kernel. Sized on first use for a (n, Q); reused for
/// every element of the same size without allocating.
template <int d>
struct ElementScratch {
  static constexpr int n_pairs = d * (d + 1) / 2;  // blocks (k, l) with k ≤ l
  Eigen::MatrixXd B;  // n × dQ: column block q is B_q = ∇N_q W_q⁻¹
  Eigen::MatrixXd P;  // d × dQ: column block q is w_q dμ/dT(T_q)
  Eigen::MatrixXd G;  // d × dQ on tensor grids: column block q is X ∇N_q
  Eigen::MatrixXd R;  // d × dQ on tensor grids: column block q is w_q dμ/dT(T_q) W_q⁻ᵀ = ∂(w_q μ)/∂G_q
  Eigen::MatrixXd C;  // n × (n_pairs·dQ): block (pair, q) is B_q · w_q H_q^{kl}
  Eigen::MatrixXd g;  // d × n: ∂E/∂X
  Eigen::MatrixXd H;  // dn × dn, component-major local order k·n + a
};

/// Completes a component-major element Hessian (d·n × d·n) whose blocks (k, l), k ≤ l, are
/// set: the blocks below are their transposes and the diagonal blocks are made exactly
/// symmetric, so that the assembled matrix is symmetric bit for bit.
template <int d, class Matrix>
void complete_symmetric(Matrix& H, int n) {
  for (int k = 0; k < d; ++k) {
    for (int l = k + 1; l < d; ++l) H.block(l * n, k * n, n, n) = H.block(k * n, l * n, n, n).transpose();
    for (int a = 0; a < n; ++a)
      for (int b = 0; b < a; ++b) {
        const double v = 0.5 * (H(k * n + a, k * n + b) + H(k * n + b, k * n + a));
        H(k * n + a, k * n + b) = v;
        H(k * n + b, k * n + a) = v;
      }
  }
}

/// E_e of one element (without ω_e). Fills s.g and s.H (component-major) as `want` asks;
/// returns +∞, leaving them unspecified, when μ is not finite at some point.
///
/// The Hessian uses H_e^{kl} = Σ_q B_q H_q^{kl} B_qᵀ, with H_q^{kl}(j, m) = d²μ/dT_kj dT_lm:
/// stacking the Q points side by side turns the sum into one n × dQ × n product per pair
/// (k ≤ l); the blocks k > l are transposes. Where the table's points are a tensor grid
/// (ShapeTable::tensor), T_q = (X ∇N_q) W_q⁻¹ and the gradient Σ_q R_q ∇N_qᵀ are taken by sum
/// factorization instead (a P3 hexahedron: 7× fewer operations).
template <int d>
double element_kernel(const Metric<d>& metric, const ShapeTable& table, const QuadratureTarget<d>* targets,
                      const NodalMatrix<d>& X, Want want, HessianMode mode, ElementScratch<d>& s) {
  const int n = table.n_nodes();
  const int Q = table.n_points();
  const bool grad = want != Want::Value;
  const bool hess = want == Want::Hessian;
  const TensorGrid* grid = table.tensor && table.dim == d ? table.tensor.get() : nullptr;
  if (grid) {
    s.G.resize(d, d * Q);
    grid_gradients(*grid, X.data(), d, s.G.data());
    if (grad) s.R.resize(d, d * Q);
  } else if (grad) {
    s.P.resize(d, d * Q);
  }
  if (hess || (grad && !grid)) s.B.resize(n, d * Q);
  if (hess) s.C.resize(n, ElementScratch<d>::n_pairs * d * Q);
  double value = 0.0;
  Eigen::Matrix<double, Eigen::Dynamic, d, Eigen::ColMajor, k_max_nodes, d> Bq(n, d);
  for (int q = 0; q < Q; ++q) {
    const QuadratureTarget<d>& t = targets[q];
    // coefficient-wise products: no GEMM packing for n × d · d × d
    if (!grid || hess) Bq.noalias() = table.dN.middleCols(q * d, d).lazyProduct(t.W_inv);
    const MatT<d> T = grid ? MatT<d>(Eigen::Map<const MatT<d>>(s.G.data() + d * d * q).lazyProduct(t.W_inv)) : MatT<d>(X.lazyProduct(Bq));
    const MetricEval<d> ev = metric.eval(T, want);
    if (!(ev.mu < std::numeric_limits<double>::infinity())) return std::numeric_limits<double>::infinity();
    value += t.weight * ev.mu;
    if (!grad) continue;
    if (grid)
      s.R.middleCols(q * d, d).noalias() = (t.weight * ev.dmu_dT).lazyProduct(t.W_inv.transpose());
    else
      s.P.middleCols(q * d, d) = t.weight * ev.dmu_dT;
    if (!grid || hess) s.B.middleCols(q * d, d) = Bq;
    if (!hess) continue;
    HessT<d> Hq = ev.d2mu_dT2;
    if (mode == HessianMode::Projected) project_isotropic<d>(T, Hq);
    Hq *= t.weight;
    int pair = 0;
    for (int k = 0; k < d; ++k)
      for (int l = k; l < d; ++l, ++pair) {
        MatT<d> Hkl;
        for (int j = 0; j < d; ++j)
          for (int m = 0; m < d; ++m) Hkl(j, m) = Hq(k + d * j, l + d * m);
        s.C.middleCols((pair * Q + q) * d, d).noalias() = Bq.lazyProduct(Hkl);
      }
  }
  if (grad && grid) {
    s.g.resize(d, n);
    grid_gradients_transpose(*grid, s.R.data(), d, s.g.data());
  } else if (grad) {
    s.g.noalias() = s.P * s.B.transpose();
  }
  if (hess) {
    s.H.resize(d * n, d * n);
    int pair = 0;
    for (int k = 0; k < d; ++k)
      for (int l = k; l < d; ++l, ++pair)
        s.H.block(k * n, l * n, n, n).noalias() = s.C.middleCols(pair * Q * d, Q * d) * s.B.transpose();
    complete_symmetric<d>(s.H, n);
  }
  return value;
}

/// Work space of element_kernel_fixed: the outputs of element_kernel for n nodes known at
/// compile time, in the same orders.
template <int d, int n>
struct FixedElementScratch {
  Eigen::Matrix<double, d, n> g;          // ∂E/∂X
  Eigen::Matrix<double, d * n, d * n> H;  // component-major local order k·n + a
};

/// element_kernel for n nodes known at compile time (linear simplices): every product is
/// fixed-size and the points are summed one by one, H_e^{kl} = Σ_q (B_q H_q^{kl}) B_qᵀ.
/// The value is element_kernel's bit for bit (assembled element values equal element_energy's).
template <int d, int n>
double element_kernel_fixed(const Metric<d>& metric, const ShapeTable& table, const QuadratureTarget<d>* targets,
                            const Eigen::Matrix<double, d, n>& X, Want want, HessianMode mode,
                            FixedElementScratch<d, n>& s) {
  const int Q = table.n_points();
  const bool grad = want != Want::Value;
  const bool hess = want == Want::Hessian;
  if (grad) s.g.setZero();
  if (hess) s.H.setZero();
  double value = 0.0;
  for (int q = 0; q < Q; ++q) {
    const QuadratureTarget<d>& t = targets[q];
    // Column block q of the n × dQ column-major table is contiguous.
    const Eigen::Matrix<double, n, d> Bq =
        Eigen::Map<const Eigen::Matrix<double, n, d>>(table.dN.data() + q * d * n) * t.W_inv;
    // T = X B_q summed over the nodes in order, as element_kernel's dynamic-size product does.
    MatT<d> T = X.col(0) * Bq.row(0);
    for (int a = 1; a < n; ++a) T.noalias() += X.col(a) * Bq.row(a);
    const MetricEval<d> ev = metric.eval(T, want);
    if (!(ev.mu < std::numeric_limits<double>::infinity())) return std::numeric_limits<double>::infinity();
    value += t.weight * ev.mu;
    if (!grad) continue;
    s.g.noalias() += (t.weight * ev.dmu_dT).lazyProduct(Bq.transpose());
    if (!hess) continue;
    HessT<d> Hq = ev.d2mu_dT2;
    if (mode == HessianMode::Projected) project_isotropic<d>(T, Hq);
    Hq *= t.weight;
    for (int k = 0; k < d; ++k)
      for (int l = k; l < d; ++l) {
        MatT<d> Hkl;
        for (int j = 0; j < d; ++j)
          for (int m = 0; m < d; ++m) Hkl(j, m) = Hq(k + d * j, l + d * m);
        const Eigen::Matrix<double, n, d> C = Bq.lazyProduct(Hkl);
        s.H.template block<n, n>(k * n, l * n).noalias() += C.lazyProduct(Bq.transpose());
      }
  }
  if (hess) complete_symmetric<d>(s.H, n);
  return value;
}

}  // namespace meshmorph::detail
