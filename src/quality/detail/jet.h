// SPDX-License-Identifier: MIT
#pragma once
#include <cmath>
#include <limits>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <Eigen/LU>

#include "meshmorph/quality/metric.h"

namespace meshmorph::detail {

/// A scalar function of vec(T) with its gradient and Hessian (second-order forward jet).
/// Only the parts that `want` asks for are filled; the others stay zero.
template <int d>
struct Jet {
  double v = 0.0;
  Eigen::Matrix<double, d * d, 1> g = Eigen::Matrix<double, d * d, 1>::Zero();
  HessT<d> H = HessT<d>::Zero();
};

inline bool needs_gradient(Want want) { return want != Want::Value; }
inline bool needs_hessian(Want want) { return want == Want::Hessian; }

/// |T|²: gradient 2 vec(T), Hessian 2 I.
template <int d>
Jet<d> frobenius_squared(const MatT<d>& T, Want want) {
  Jet<d> j;
  j.v = T.squaredNorm();
  if (needs_gradient(want)) j.g = 2.0 * T.reshaped();
  if (needs_hessian(want)) j.H = 2.0 * HessT<d>::Identity();
  return j;
}

/// τ = det T: ∂τ/∂T = cof T; the Hessian blocks (column j, column l) are −ε_jlm [t_m]_× in
/// 3D (t_m the columns of T) and ±1 on the anti-diagonal pattern in 2D. docs/metrics.md.
template <int d>
Jet<d> determinant(const MatT<d>& T, Want want) {
  Jet<d> j;
  j.v = T.determinant();
  if constexpr (d == 2) {
    if (needs_gradient(want)) j.g << T(1, 1), -T(0, 1), -T(1, 0), T(0, 0);
    if (needs_hessian(want)) {
      j.H(0, 3) = j.H(3, 0) = 1.0;
      j.H(1, 2) = j.H(2, 1) = -1.0;
    }
  } else {
    static_assert(d == 3);
    if (needs_gradient(want)) {
      j.g.template segment<3>(0) = T.col(1).cross(T.col(2));
      j.g.template segment<3>(3) = T.col(2).cross(T.col(0));
      j.g.template segment<3>(6) = T.col(0).cross(T.col(1));
    }
    if (needs_hessian(want)) {
      auto skew = [](const Eigen::Vector3d& a) {
        Eigen::Matrix3d s;
        s << 0, -a(2), a(1), a(2), 0, -a(0), -a(1), a(0), 0;
        return s;
      };
      // Cyclic (j, l, m): block(j, l) = −[t_m]×, block(l, j) = +[t_m]×.
      for (int c = 0; c < 3; ++c) {
        const int jc = c, l = (c + 1) % 3, m = (c + 2) % 3;
        const Eigen::Matrix3d s = skew(T.col(m));
        j.H.template block<3, 3>(3 * jc, 3 * l) = -s;
        j.H.template block<3, 3>(3 * l, 3 * jc) = s;
      }
    }
  }
  return j;
}

/// φ(a) given φ(a.v), φ'(a.v), φ''(a.v): chain rule ∇φ = φ' ∇a, ∇²φ = φ'' ∇a∇aᵀ + φ' ∇²a.
template <int d>
Jet<d> compose(const Jet<d>& a, double f, double f1, double f2, Want want) {
  Jet<d> j;
  j.v = f;
  if (needs_gradient(want)) j.g = f1 * a.g;
  if (needs_hessian(want)) j.H = f2 * a.g * a.g.transpose() + f1 * a.H;
  return j;
}

/// a·b by the product rule.
template <int d>
Jet<d> product(const Jet<d>& a, const Jet<d>& b, Want want) {
  Jet<d> j;
  j.v = a.v * b.v;
  if (needs_gradient(want)) j.g = a.g * b.v + a.v * b.g;
  if (needs_hessian(want)) {
    j.H = a.H * b.v + a.v * b.H + a.g * b.g.transpose() + b.g * a.g.transpose();
  }
  return j;
}

/// α·a + β (β only shifts the value).
template <int d>
Jet<d> affine(const Jet<d>& a, double alpha, double beta, Want want) {
  Jet<d> j;
  j.v = alpha * a.v + beta;
  if (needs_gradient(want)) j.g = alpha * a.g;
  if (needs_hessian(want)) j.H = alpha * a.H;
  return j;
}

/// α·a + β·b.
template <int d>
Jet<d> combine(double alpha, const Jet<d>& a, double beta, const Jet<d>& b, Want want) {
  Jet<d> j;
  j.v = alpha * a.v + beta * b.v;
  if (needs_gradient(want)) j.g = alpha * a.g + beta * b.g;
  if (needs_hessian(want)) j.H = alpha * a.H + beta * b.H;
  return j;
}

/// The MetricEval of a jet (vec(T) gradient reshaped back to d×d).
template <int d>
MetricEval<d> to_eval(const Jet<d>& j) {
  MetricEval<d> e;
  e.mu = j.v;
  e.dmu_dT = j.g.reshaped(d, d);
  e.d2mu_dT2 = j.H;
  return e;
}

/// The evaluation outside a barrier metric's domain: μ = +∞, derivatives zero.
template <int d>
MetricEval<d> infinite_eval() {
  MetricEval<d> e;
  e.mu = std::numeric_limits<double>::infinity();
  return e;
}

}  // namespace meshmorph::detail
