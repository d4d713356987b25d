// SPDX-License-Identifier: MIT
#include "meshmorph/quality/edge_quality.h"

#include <array>
#include <cmath>
#include <limits>
#include <string>

#include <Eigen/LU>

#include "meshmorph/error.h"
#include "meshmorph/quality/element_quality.h"
#include "quality/detail/jet.h"

namespace meshmorph {
namespace {

// The regular simplex of unit edge (W = ideal_jacobian, quality/element_quality.h): its
// edges, its volume and the constant C of eq. 3 that makes its quality 1.
template <int d>
struct RegularSimplex {
  std::array<Eigen::Matrix<double, d, 1>, d * (d + 1) / 2> edges;
  double volume = 0.0;
  double constant = 0.0;
};

template <int d>
const RegularSimplex<d>& regular_simplex() {
  static const RegularSimplex<d> simplex = [] {
    const MatT<d> W = ideal_jacobian(d == 2 ? ElementType::Triangle : ElementType::Tetrahedron);
    RegularSimplex<d> r;
    std::size_t k = 0;
    for (int i = 0; i < d; ++i) r.edges[k++] = W.col(i);  // from corner 0
    for (int i = 0; i < d; ++i)
      for (int j = i + 1; j < d; ++j) r.edges[k++] = W.col(j) - W.col(i);
    r.volume = W.determinant() / (d == 2 ? 2.0 : 6.0);
    r.constant = d == 2 ? 4.0 * std::sqrt(3.0) : 36.0 * std::sqrt(2.0);
    return r;
  }();
  return simplex;
}

// Adds lᵈ = s^{d/2}, s = |T e|², to the jet L: ∇s = vec(2 T e eᵀ), ∇²s = 2 (e eᵀ) ⊗ I
// (vec is column-major), accumulated in place without forming the jet of s.
template <int d>
void add_edge_power(detail::Jet<d>& L, const MatT<d>& T, const Eigen::Matrix<double, d, 1>& e, Want want) {
  const Eigen::Matrix<double, d, 1> te = T * e;
  const double s = te.squaredNorm();
  const double k = 0.5 * d;
  L.v += std::pow(s, k);
  if (!detail::needs_gradient(want)) return;
  const double f1 = k * std::pow(s, k - 1.0);
  const Eigen::Matrix<double, d * d, 1> gs = (2.0 * te * e.transpose()).reshaped();
  L.g += f1 * gs;
  if (!detail::needs_hessian(want)) return;
  // In 3D (s^{3/2})'' = ¾ s^{−1/2} multiplies ∇s∇sᵀ = O(s): the product tends to 0 at s = 0.
  const double f2 = s > 0.0 ? k * (k - 1.0) * std::pow(s, k - 2.0) : 0.0;
  L.H.noalias() += f2 * gs * gs.transpose();
  for (int b = 0; b < d; ++b)
    for (int c = 0; c < d; ++c) L.H.template block<d, d>(d * b, d * c).diagonal().array() += 2.0 * f1 * e(b) * e(c);
}

}  // namespace

template <int d>
EdgeQuality<d>::EdgeQuality(EdgeQualityOptions options) : options_(options) {
  MESHMORPH_CHECK(options.delta >= 0.0 && std::isfinite(options.delta),
                  "edge_quality: delta must be finite and >= 0, got " + std::to_string(options.delta));
  MESHMORPH_CHECK(options.n < 0.0 && std::isfinite(options.n),
                  "edge_quality: n must be finite and < 0, got " + std::to_string(options.n));
}

// F = exp(n·g) with g = log C + log h(V) − log L, L = Σ lⱼᵈ: logarithms turn the quotient
// into sums, and h'/h = 1/r, h''/h − (h'/h)² = 2δ²/(r³h) − 1/r² with r = √(V² + 4δ²).
template <int d>
MetricEval<d> EdgeQuality<d>::eval(const MatT<d>& T, Want want) const {
  const RegularSimplex<d>& reg = regular_simplex<d>();
  const double delta = options_.delta;
  const detail::Jet<d> V = detail::affine(detail::determinant(T, want), reg.volume, 0.0, want);
  const double r = std::sqrt(V.v * V.v + 4.0 * delta * delta);
  // h = ½(V + r), written without cancellation for V < 0: (r + V)(r − V) = 4δ².
  const double h = V.v >= 0.0 ? 0.5 * (V.v + r) : 2.0 * delta * delta / (r - V.v);
  if (!(h > 0.0)) return detail::infinite_eval<d>();  // δ = 0 and V ≤ 0: q* = 0, F = +∞

  detail::Jet<d> L;
  for (const auto& e : reg.edges) add_edge_power<d>(L, T, e, want);
  if (!(L.v > 0.0)) return detail::infinite_eval<d>();  // T = 0: every edge collapsed

  const detail::Jet<d> log_h = detail::compose(V, std::log(h), 1.0 / r, 2.0 * delta * delta / (r * r * r * h) - 1.0 / (r * r), want);
  const detail::Jet<d> log_L = detail::compose(L, std::log(L.v), 1.0 / L.v, -1.0 / (L.v * L.v), want);
  const detail::Jet<d> g = detail::affine(detail::combine(1.0, log_h, -1.0, log_L, want), 1.0, std::log(reg.constant), want);
  const double n = options_.n;
  const double F = std::exp(n * g.v);
  return detail::to_eval(detail::compose(g, F, n * F, n * n * F, want));
}

template <int d>
double EdgeQuality<d>::volume(const MatT<d>& T) {
  return regular_simplex<d>().volume * T.determinant();
}

// With g = log F / n: g_δ = 2δ/(rh), g_δδ = 2/(rh) − 8δ²/(r³h) − 4δ²/(r²h²), g_δV = −4δ/r³ and
// dg = dV/r − dL/L along dT; then F_δ = nF g_δ, F_δδ = nF(n g_δ² + g_δδ) and
// F_δT:dT = nF(n g_δ dg + g_δV dV) (docs/metrics.md#edge_quality).
template <int d>
typename EdgeQuality<d>::DeltaDerivatives EdgeQuality<d>::delta_derivatives(const MatT<d>& T, const MatT<d>& dT) const {
  const RegularSimplex<d>& reg = regular_simplex<d>();
  const double delta = options_.delta;
  const double V = volume(T);
  // d det T along dT = Σ cof(T) : dT.
  double ddet = 0.0;
  if constexpr (d == 2) {
    ddet = dT(0, 0) * T(1, 1) + T(0, 0) * dT(1, 1) - dT(1, 0) * T(0, 1) - T(1, 0) * dT(0, 1);
  } else {
    ddet = dT.col(0).dot(T.col(1).cross(T.col(2))) + dT.col(1).dot(T.col(2).cross(T.col(0))) +
           dT.col(2).dot(T.col(0).cross(T.col(1)));
  }
  const double dV = reg.volume * ddet;
  double L = 0.0, dL = 0.0;
  for (const auto& e : reg.edges) {
    const Eigen::Matrix<double, d, 1> te = T * e;
    const double s = te.squaredNorm();
    L += std::pow(s, 0.5 * d);
    dL += d * std::pow(s, 0.5 * d - 1.0) * te.dot(dT * e);
  }
  const double r = std::sqrt(V * V + 4.0 * delta * delta);
  const double h = V >= 0.0 ? 0.5 * (V + r) : 2.0 * delta * delta / (r - V);
  constexpr double inf = std::numeric_limits<double>::infinity();
  if (!(h > 0.0) || !(L > 0.0)) return {inf, inf, inf};
  const double n = options_.n;
  const double F = std::exp(n * (std::log(reg.constant) + std::log(h) - std::log(L)));
  const double g_d = 2.0 * delta / (r * h);
  const double g_dd = 2.0 / (r * h) - 8.0 * delta * delta / (r * r * r * h) - 4.0 * delta * delta / (r * r * h * h);
  const double g_dV = -4.0 * delta / (r * r * r);
  const double dg = dV / r - dL / L;
  return {n * F * g_d, n * F * (n * g_d * g_d + g_dd), n * F * (n * g_d * dg + g_dV * dV)};
}

template class EdgeQuality<2>;
template class EdgeQuality<3>;

}  // namespace meshmorph
