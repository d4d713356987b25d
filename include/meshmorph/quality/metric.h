// SPDX-License-Identifier: MIT
#pragma once
#include <string_view>

#include <Eigen/Core>

namespace meshmorph {

/// Notation (DESIGN §2, used in every metric kernel):
///   A  element Jacobian ∂x/∂ξ at a point (d×d)
///   W  target Jacobian (input element, or the ideal element)
///   T  = A W⁻¹, the map from target to current element
///   τ  = det T;  |T| the Frobenius norm
///   μ(T) the metric; vec(T) stacks T column-major, so d²μ/dT² is (d²×d²) on vec(T).
template <int d> using MatT = Eigen::Matrix<double, d, d>;
template <int d> using HessT = Eigen::Matrix<double, d * d, d * d>;

/// What Metric::eval must fill; later members include the earlier ones.
enum class Want { Value, Gradient, Hessian };

/// Result of a metric evaluation. `mu` is +∞ outside the metric's domain (e.g. τ ≤ 0 for
/// barrier metrics); the derivatives are then unspecified.
template <int d>
struct MetricEval {
  double mu = 0.0;
  MatT<d> dmu_dT = MatT<d>::Zero();
  HessT<d> d2mu_dT2 = HessT<d>::Zero();
};

/// A mesh-quality metric as a function of T. Stateless after construction: one instance
/// may serve all threads.
template <int d>
class Metric {
 public:
  virtual ~Metric() = default;
  virtual MetricEval<d> eval(const MatT<d>& T, Want want) const = 0;
  virtual std::string_view name() const = 0;
};

}  // namespace meshmorph
