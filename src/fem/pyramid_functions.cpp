// SPDX-License-Identifier: MIT
#include "fem/detail/pyramid_functions.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace meshmorph::detail {
namespace {

// coef · u^a v^b h^c ζ^d; c may be negative.
struct Term {
  double coef;
  int a, b, c, d;
};

using Terms = std::vector<Term>;

// The functions of the space, one term each.
std::vector<Terms> functions(int p) {
  std::vector<Terms> out;
  for (int i = 0; i <= p; ++i)
    for (int j = 0; j <= p; ++j) {
      const int m = std::max(i, j);
      for (int k = 0; k <= p - m; ++k) out.push_back({{1.0, i, j, m, k}});
    }
  return out;
}

// ∂/∂ξ, ∂/∂η, ∂/∂ζ (k = 0, 1, 2) with u_ξ = v_η = 1/h, u_ζ = u/h, v_ζ = v/h, h_ζ = −1;
// `collapsed`: ∂/∂u ÷ h, ∂/∂v ÷ h, ∂/∂ζ at fixed (u, v).
Terms derive(const Terms& f, int k, bool collapsed) {
  Terms out;
  const auto add = [&](double coef, int a, int b, int c, int d) {
    if (coef != 0.0) out.push_back({coef, a, b, c, d});
  };
  for (const Term& t : f) {
    if (k == 0) add(t.coef * t.a, t.a - 1, t.b, t.c - 1, t.d);
    if (k == 1) add(t.coef * t.b, t.a, t.b - 1, t.c - 1, t.d);
    if (k == 2) {
      add(t.coef * (collapsed ? -t.c : t.a + t.b - t.c), t.a, t.b, t.c - 1, t.d);
      add(t.coef * t.d, t.a, t.b, t.c, t.d - 1);
    }
  }
  return out;
}

// Σ coef u^a v^b h^c ζ^d; a zero factor of u, v or ζ ends a term before h^c, which may be
// infinite at the apex.
double evaluate(const Terms& f, double u, double v, double h, double z) {
  double sum = 0.0;
  for (const Term& t : f) {
    const double x = t.coef * std::pow(u, t.a) * std::pow(v, t.b) * std::pow(z, t.d);
    if (x != 0.0) sum += x * std::pow(h, t.c);
  }
  return sum;
}

}  // namespace

Eigen::MatrixXd pyramid_functions(int order, const Eigen::Vector3d& xi, int derivatives) {
  const std::vector<Terms> f = functions(order);
  const double h = 1 - xi(2), u = h > 0 ? xi(0) / h : 0.0, v = h > 0 ? xi(1) / h : 0.0;
  const int n = static_cast<int>(f.size()), cols = derivatives == 0 ? 1 : derivatives == 1 ? 3 : 9;
  Eigen::MatrixXd out(n, cols);
  for (int a = 0; a < n; ++a) {
    const Terms& fa = f[static_cast<std::size_t>(a)];
    if (derivatives == 0) out(a, 0) = evaluate(fa, u, v, h, xi(2));
    for (int k = 0; k < 3 && derivatives > 0; ++k) {
      const Terms dk = derive(fa, k, false);
      if (derivatives == 1) out(a, k) = evaluate(dk, u, v, h, xi(2));
      for (int l = 0; l < 3 && derivatives == 2; ++l) out(a, 3 * k + l) = evaluate(derive(dk, l, false), u, v, h, xi(2));
    }
  }
  return out;
}

Eigen::MatrixXd pyramid_collapsed_gradients(int order, const Eigen::Vector3d& uvz) {
  const std::vector<Terms> f = functions(order);
  const int n = static_cast<int>(f.size());
  Eigen::MatrixXd out(n, 3);
  for (int a = 0; a < n; ++a)
    for (int k = 0; k < 3; ++k) out(a, k) = evaluate(derive(f[static_cast<std::size_t>(a)], k, true), uvz(0), uvz(1), 1 - uvz(2), uvz(2));
  return out;
}

}  // namespace meshmorph::detail
