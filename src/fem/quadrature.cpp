// SPDX-License-Identifier: MIT
#include "meshmorph/fem/quadrature.h"

#include <cmath>
#include <map>
#include <memory>
#include <mutex>

#include <Eigen/Eigenvalues>

#include "meshmorph/error.h"

namespace meshmorph {
namespace {

#include "fem/detail/simplex_rules.inc"

struct Rule1d {
  Eigen::VectorXd x, w;
};

// n-point Gauss–Jacobi rule for the weight (1 − t)^α on [0, 1] by Golub–Welsch: the nodes
// are the eigenvalues of the Jacobi matrix of the orthogonal polynomials of (1−x)^α on
// [−1, 1], the weights μ₀ times the squared first eigenvector components.
Rule1d gauss_jacobi(int n, int alpha) {
  const double a = alpha, b = 0.0;
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) {
    const double s = 2.0 * i + a + b;
    J(i, i) = i == 0 ? (b - a) / (a + b + 2) : (b * b - a * a) / (s * (s + 2));
    if (i + 1 < n) {
      const double k = i + 1.0, t = 2.0 * k + a + b;
      J(i, i + 1) = J(i + 1, i) = std::sqrt(4 * k * (k + a) * (k + b) * (k + a + b) / (t * t * (t + 1) * (t - 1)));
    }
  }
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(J);
  const double mu0 = std::pow(2.0, a + b + 1) / (a + b + 1);  // ∫ (1−x)^α dx on [−1, 1], β = 0
  Rule1d r{Eigen::VectorXd(n), Eigen::VectorXd(n)};
  for (int i = 0; i < n; ++i) {
    r.x(i) = (eig.eigenvalues()(i) + 1) / 2;  // to [0, 1]
    r.w(i) = mu0 * eig.eigenvectors()(0, i) * eig.eigenvectors()(0, i) / std::pow(2.0, a + 1);
  }
  return r;
}

int points_for_degree(int degree) { return degree / 2 + 1; }  // Gauss: exact to 2n − 1

QuadratureRule make_rule(ElementType type, int degree) {
  QuadratureRule q{type, degree, {}, {}};
  const int n = points_for_degree(std::max(degree, 0));
  const int dim = topological_dim(type);
  if (type == ElementType::Point) {
    q.points = Eigen::MatrixXd(0, 1);
    q.weights = Eigen::VectorXd::Ones(1);
    return q;
  }
  if (!is_simplex(type) || type == ElementType::Line) {  // Gauss–Legendre on [−1, 1]^d
    const auto g = gauss_jacobi(n, 0);
    const int np = static_cast<int>(std::pow(n, dim));
    q.points.resize(dim, np);
    q.weights.resize(np);
    for (int p = 0; p < np; ++p) {
      int r = p;
      double w = 1.0;
      for (int k = 0; k < dim; ++k, r /= n) {
        q.points(k, p) = 2 * g.x(r % n) - 1;
        w *= 2 * g.w(r % n);
      }
      q.weights(p) = w;
    }
    return q;
  }
  // A symmetric rule where one exists (far fewer points: 24 instead of 64 at degree 6 on a
  // tetrahedron), else the Stroud conical product.
  for (const auto& r : k_simplex_rules) {
    if (r.dim != dim || r.degree != degree) continue;
    q.points.resize(dim, r.n_points);
    q.weights.resize(r.n_points);
    for (int p = 0; p < r.n_points; ++p) {
      for (int k = 0; k < dim; ++k) q.points(k, p) = r.data[p * (dim + 1) + k];
      q.weights(p) = r.data[p * (dim + 1) + dim];
    }
    return q;
  }
  // Stroud conical product on the unit simplex: x = s(1−t)(1−r), y = t(1−r), z = r with
  // Gauss–Jacobi rules absorbing the collapse Jacobian (1−t)(1−r)².
  const auto gs = gauss_jacobi(n, 0), gt = gauss_jacobi(n, 1), gr = gauss_jacobi(n, 2);
  const int np = dim == 2 ? n * n : n * n * n;
  q.points.resize(dim, np);
  q.weights.resize(np);
  int p = 0;
  for (int k = 0; k < (dim == 3 ? n : 1); ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i, ++p) {
        const double s = gs.x(i), t = gt.x(j);
        if (dim == 2) {
          q.points.col(p) << s * (1 - t), t;
          q.weights(p) = gs.w(i) * gt.w(j);
        } else {
          const double r = gr.x(k);
          q.points.col(p) << s * (1 - t) * (1 - r), t * (1 - r), r;
          q.weights(p) = gs.w(i) * gt.w(j) * gr.w(k);
        }
      }
  return q;
}

}  // namespace

const QuadratureRule& quadrature_rule(ElementType type, int degree) {
  MESHMORPH_CHECK(degree >= 0 && degree <= 40, "quadrature degree out of range");
  static std::mutex mutex;
  static std::map<std::pair<ElementType, int>, std::unique_ptr<QuadratureRule>> cache;
  std::lock_guard lock(mutex);
  auto& slot = cache[{type, degree}];
  if (!slot) slot = std::make_unique<QuadratureRule>(make_rule(type, degree));
  return *slot;
}

int metric_quadrature_degree(ElementType type, int order) {
  if (type == ElementType::Point) return 0;
  if (is_simplex(type)) return order == 1 && type != ElementType::Line ? 1 : 2 * order;
  return 2 * order + 1;
}

}  // namespace meshmorph
