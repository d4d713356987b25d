// SPDX-License-Identifier: MIT
#pragma once
#include <span>

#include <Eigen/Core>

#include "meshmorph/energy/target.h"
#include "meshmorph/quality/metric.h"

namespace meshmorph {

/// How the Hessian of an energy is formed.
enum class HessianMode {
  /// d²μ/dT² is projected onto the PSD cone at every quadrature point before the chain rule
  /// (quality/spd_projection.h), so element and assembled Hessians are PSD for every order.
  Projected,
  /// The exact Hessian (DESIGN §6: the unprojected step is tried first).
  Exact,
};

/// Energy of one element with its nodal derivatives.
struct ElementEnergy {
  double value = 0.0;         ///< +∞ when μ is +∞ (or not finite) at any quadrature point
  Eigen::VectorXd gradient;   ///< d·n, entry d·a + k = ∂E/∂X(k, a) (vec(X) column-major)
  Eigen::MatrixXd hessian;    ///< (d·n) × (d·n) in the same ordering, symmetric
};

/// The energy of a metric over one element: E_e = Σ_q w_q |det W_q| μ(T_q), T_q = A_q W_q⁻¹,
/// A_q = X · ∇N_q (paper 000 eq. 7; paper 003 eq. 4). T is linear in X, with
/// ∂T/∂X(k, a) = e_k (∇N_a)ᵀ W⁻¹, which gives the gradient and Hessian by the chain rule.
///
/// `table` is the basis at the quadrature points, `targets` one entry per point, X the d × n
/// nodal coordinates in the internal (Gmsh) order. Fills what `want` asks for; when the value
/// is +∞ the derivatives are unspecified. Works for any supported type and order (n ≤ 125).
template <int d>
ElementEnergy element_energy(const Metric<d>& metric, const ShapeTable& table,
                             std::span<const QuadratureTarget<d>> targets,
                             const Eigen::Matrix<double, d, Eigen::Dynamic>& X, Want want,
                             HessianMode mode = HessianMode::Projected);

}  // namespace meshmorph
