// SPDX-License-Identifier: MIT
#pragma once
#include <algorithm>
#include <cmath>
#include <functional>
#include <type_traits>

#include <Eigen/Core>
#include <gtest/gtest.h>

namespace meshmorph::test {

/// Five-point central difference of a function of vec(x) along coordinate i with step h:
/// (−f(x+2h) + 8f(x+h) − 8f(x−h) + f(x−2h)) / 12h, truncation error O(h⁴).
template <typename F, typename X>
auto five_point(const F& f, const X& x, int i, double h) {
  using R = std::decay_t<decltype(f(x))>;  // evaluated: no expression template outlives f's results
  auto at = [&](double t) {
    X y = x;
    y(i) += t;
    return R(f(y));
  };
  const R m2 = at(-2 * h), m1 = at(-h), p1 = at(h), p2 = at(2 * h);
  return R(((m2 - p2) + 8.0 * (p1 - m1)) / (12.0 * h));
}

/// Relative error |a − b| / max(1, |a|) in the Frobenius norm (a = analytic).
template <typename A, typename B>
double relative_error(const A& a, const B& b) {
  return (a - b).norm() / std::max(1.0, a.norm());
}

/// Step for differences: h = 1e-3·min(1, scale), with `scale` the distance to the nearest
/// singularity of f the caller knows of (e.g. τ/|cof T| for a barrier in det T), so that f
/// varies on the scale 1 or `scale`. Relative to the derivative, the five-point rule then
/// errs by about (h/scale)⁴ ≈ 1e-12 (truncation) plus ε·scale/h ≈ 1e-13 (rounding).
inline double fd_step(double scale) { return 1e-3 * std::min(1.0, scale); }

/// Expects `grad` to match five-point differences of `f` at x (both over vec(x)).
template <typename F, typename X, typename G>
void expect_gradient_matches_fd(const F& f, const X& x, const G& grad, double h, double rel_tol) {
  G fd = grad;
  for (int i = 0; i < x.size(); ++i) fd(i) = five_point(f, x, i, h);
  const double err = relative_error(grad, fd);
  EXPECT_LE(err, rel_tol) << "analytic:\n" << grad << "\nfinite differences:\n" << fd;
}

/// Expects `hess` to match five-point differences of the gradient function `g` at x.
template <typename Gf, typename X, typename H>
void expect_hessian_matches_fd(const Gf& g, const X& x, const H& hess, double h, double rel_tol) {
  H fd = hess;
  for (int i = 0; i < x.size(); ++i) fd.col(i) = five_point(g, x, i, h);
  const double err = relative_error(hess, fd);
  EXPECT_LE(err, rel_tol) << "analytic:\n" << hess << "\nfinite differences:\n" << fd;
}

}  // namespace meshmorph::test
