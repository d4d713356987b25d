// SPDX-License-Identifier: MIT
#include "meshmorph/fem/lagrange_basis.h"

#include <array>
#include <map>
#include <memory>
#include <mutex>

#include <Eigen/LU>

#include "fem/detail/pyramid_functions.h"

namespace meshmorph {
namespace {

// Exponents of the monomials spanning the element's space: total degree ≤ p on simplices,
// degree ≤ p in each variable on tensor cells (lines are both).
Eigen::MatrixXi monomial_exponents(ElementType type, int p, int dim) {
  std::vector<std::array<int, 3>> e;
  const bool simplex = is_simplex(type);
  const int pz = dim > 2 ? p : 0, py = dim > 1 ? p : 0, px = dim > 0 ? p : 0;
  for (int k = 0; k <= pz; ++k)
    for (int j = 0; j <= py; ++j)
      for (int i = 0; i <= px; ++i)
        if (!simplex || i + j + k <= p) e.push_back({i, j, k});
  Eigen::MatrixXi out(dim, static_cast<Eigen::Index>(e.size()));
  for (std::size_t m = 0; m < e.size(); ++m)
    for (int k = 0; k < dim; ++k) out(k, static_cast<Eigen::Index>(m)) = e[m][static_cast<std::size_t>(k)];
  return out;
}

double ipow(double x, int n) {
  double r = 1.0;
  for (int i = 0; i < n; ++i) r *= x;
  return r;
}

}  // namespace

LagrangeBasis::LagrangeBasis(ElementType type, int order) : ref_(&reference_element(type, order)) {
  const int n = ref_->n_nodes(), d = ref_->dim;
  if (type == ElementType::Prism) {  // N_a(ξ, η, ζ) = L_i(ξ, η) ℓ_k(ζ): node a is triangle node i at line node k
    triangle_ = std::make_shared<const LagrangeBasis>(ElementType::Triangle, order);
    segment_ = std::make_shared<const LagrangeBasis>(ElementType::Line, order);
    const Eigen::MatrixXd& tri = triangle_->reference().nodes;
    const Eigen::MatrixXd& line = segment_->reference().nodes;
    for (int a = 0; a < n; ++a) {
      std::array<int, 2> ik{-1, -1};
      for (int i = 0; i < tri.cols(); ++i)
        if ((tri.col(i) - ref_->nodes.col(a).head<2>()).norm() < 1e-12) ik[0] = i;
      for (int k = 0; k < line.cols(); ++k)
        if (std::abs(line(0, k) - ref_->nodes(2, a)) < 1e-12) ik[1] = k;
      factors_.push_back(ik);
    }
    return;
  }
  if (type == ElementType::Pyramid) {  // rational: the nodal combinations of the pyramidal functions
    Eigen::MatrixXd V(n, n);
    for (int b = 0; b < n; ++b) V.row(b) = detail::pyramid_functions(order, ref_->nodes.col(b), 0).transpose();
    coeffs_ = V.fullPivLu().inverse();
    return;
  }
  exponents_ = monomial_exponents(type, order, d);
  Eigen::MatrixXd V(n, n);  // V(b, m) = monomial m at node b
  for (int b = 0; b < n; ++b)
    for (int m = 0; m < n; ++m) {
      double v = 1.0;
      for (int k = 0; k < d; ++k) v *= ipow(ref_->nodes(k, b), exponents_(k, m));
      V(b, m) = v;
    }
  coeffs_ = V.fullPivLu().inverse();  // N_a = Σ_m coeffs_(m, a) monomial_m
}

Eigen::VectorXd LagrangeBasis::values(const Eigen::VectorXd& xi) const {
  if (type() == ElementType::Pyramid) return coeffs_.transpose() * detail::pyramid_functions(order(), xi, 0);
  if (type() == ElementType::Prism) {
    const Eigen::VectorXd L = triangle_->values(xi.head(2)), l = segment_->values(xi.tail(1));
    Eigen::VectorXd N(n());
    for (int a = 0; a < n(); ++a) N(a) = L(factors_[a][0]) * l(factors_[a][1]);
    return N;
  }
  const int n = this->n(), d = dim();
  Eigen::VectorXd mono(n);
  for (int m = 0; m < n; ++m) {
    double v = 1.0;
    for (int k = 0; k < d; ++k) v *= ipow(xi(k), exponents_(k, m));
    mono(m) = v;
  }
  return coeffs_.transpose() * mono;
}

Eigen::MatrixXd LagrangeBasis::gradients(const Eigen::VectorXd& xi) const {
  if (type() == ElementType::Pyramid) return coeffs_.transpose() * detail::pyramid_functions(order(), xi, 1);
  if (type() == ElementType::Prism) {
    const LagrangeBasis &tri = *triangle_, &line = *segment_;
    const Eigen::VectorXd L = tri.values(xi.head(2)), l = line.values(xi.tail(1));
    const Eigen::MatrixXd dL = tri.gradients(xi.head(2)), dl = line.gradients(xi.tail(1));
    Eigen::MatrixXd G(n(), 3);
    for (int a = 0; a < n(); ++a) {
      const int i = factors_[a][0], k = factors_[a][1];
      G.row(a) << dL(i, 0) * l(k), dL(i, 1) * l(k), L(i) * dl(k, 0);
    }
    return G;
  }
  const int n = this->n(), d = dim();
  Eigen::MatrixXd dmono(n, d);
  for (int m = 0; m < n; ++m)
    for (int g = 0; g < d; ++g) {
      double v = 1.0;
      for (int k = 0; k < d; ++k) {
        const int e = exponents_(k, m);
        if (k == g) {
          v *= e == 0 ? 0.0 : e * ipow(xi(k), e - 1);
        } else {
          v *= ipow(xi(k), e);
        }
      }
      dmono(m, g) = v;
    }
  return coeffs_.transpose() * dmono;
}

Eigen::MatrixXd LagrangeBasis::hessians(const Eigen::VectorXd& xi) const {
  if (type() == ElementType::Pyramid) return coeffs_.transpose() * detail::pyramid_functions(order(), xi, 2);
  if (type() == ElementType::Prism) {
    const LagrangeBasis &tri = *triangle_, &line = *segment_;
    const Eigen::VectorXd L = tri.values(xi.head(2)), l = line.values(xi.tail(1));
    const Eigen::MatrixXd dL = tri.gradients(xi.head(2)), dl = line.gradients(xi.tail(1));
    const Eigen::MatrixXd ddL = tri.hessians(xi.head(2)), ddl = line.hessians(xi.tail(1));
    Eigen::MatrixXd H(n(), 9);
    for (int a = 0; a < n(); ++a) {
      const int i = factors_[a][0], k = factors_[a][1];
      const double xz = dL(i, 0) * dl(k, 0), yz = dL(i, 1) * dl(k, 0);
      H.row(a) << ddL(i, 0) * l(k), ddL(i, 1) * l(k), xz, ddL(i, 2) * l(k), ddL(i, 3) * l(k), yz, xz, yz, L(i) * ddl(k, 0);
    }
    return H;
  }
  const int n = this->n(), d = dim();
  Eigen::MatrixXd ddmono(n, d * d);
  for (int m = 0; m < n; ++m)
    for (int g = 0; g < d; ++g)
      for (int h = 0; h < d; ++h) {
        double v = 1.0;
        for (int k = 0; k < d; ++k) {
          const int e = exponents_(k, m), times = (k == g) + (k == h);  // differentiate times ∈ {0, 1, 2}
          if (e < times) {
            v = 0.0;
            break;
          }
          v *= (times == 0 ? 1 : times == 1 ? e : e * (e - 1)) * ipow(xi(k), e - times);
        }
        ddmono(m, g * d + h) = v;
      }
  return coeffs_.transpose() * ddmono;
}

const LagrangeBasis& lagrange_basis(ElementType type, int order) {
  static std::mutex mutex;
  static std::map<std::pair<ElementType, int>, std::unique_ptr<LagrangeBasis>> cache;
  std::lock_guard lock(mutex);
  auto& slot = cache[{type, order}];
  if (!slot) slot = std::make_unique<LagrangeBasis>(type, order);
  return *slot;
}

}  // namespace meshmorph
