// SPDX-License-Identifier: MIT
#include "meshmorph/fem/quadrature.h"

#include <cmath>
#include <map>
#include <memory>
#include <mutex>
#include <tuple>

#include <Eigen/Eigenvalues>

#include "meshmorph/error.h"

namespace meshmorph {
namespace {

#include "fem/detail/simplex_rules.inc"

struct Rule1d {
  Eigen::VectorXd x, w;
};

// n-point Gauss–Jacobi rule for the weight (1 − t)^α t^β on [0, 1] by Golub–Welsch: the
// nodes are the eigenvalues of the Jacobi matrix of the orthogonal polynomials of
// (1 − x)^α (1 + x)^β on [−1, 1], the weights μ₀ times the squared first eigenvector components.
Rule1d gauss_jacobi(int n, int alpha, int beta = 0) {
  const double a = alpha, b = beta;
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
  // ∫ (1 − t)^α t^β dt on [0, 1] = α! β! / (α + β + 1)!
  const auto factorial = [](int k) {
    double f = 1.0;
    for (int i = 2; i <= k; ++i) f *= i;
    return f;
  };
  const double mu0 = factorial(alpha) * factorial(beta) / factorial(alpha + beta + 1);
  Rule1d r{Eigen::VectorXd(n), Eigen::VectorXd(n)};
  for (int i = 0; i < n; ++i) {
    r.x(i) = (eig.eigenvalues()(i) + 1) / 2;  // to [0, 1]
    r.w(i) = mu0 * eig.eigenvectors()(0, i) * eig.eigenvectors()(0, i);
  }
  return r;
}

// n-point Gauss–Lobatto–Jacobi rule for the weight 1 − t on [0, 1]: 0, 1 and the zeros of the
// Jacobi polynomial of (1 − t)² t, exact to degree 2n − 3; each weight is ∫ ℓ_i(t)(1 − t) dt
// of the node's Lagrange polynomial, by the n-point Gauss–Jacobi rule (exact to 2n − 1).
Rule1d gauss_lobatto_jacobi(int n) {
  Rule1d r{Eigen::VectorXd(n), Eigen::VectorXd::Zero(n)};
  r.x(0) = 0.0;
  r.x(n - 1) = 1.0;
  if (n > 2) r.x.segment(1, n - 2) = gauss_jacobi(n - 2, 2, 1).x;
  const Rule1d g = gauss_jacobi(n, 1);
  for (int i = 0; i < n; ++i)
    for (int q = 0; q < n; ++q) {
      double l = g.w(q);
      for (int j = 0; j < n; ++j)
        if (j != i) l *= (g.x(q) - r.x(j)) / (r.x(i) - r.x(j));
      r.w(i) += l;
    }
  return r;
}

// n-point Gauss–Lobatto rule on [0, 1]: ±1 and the zeros of P'_{n−1} on [−1, 1], found by
// Newton on (1 − x²) P'_{n−1} = (n−1)(P_{n−2} − x P_{n−1}) from the Chebyshev–Lobatto points;
// weights 2 / (n(n−1) P_{n−1}(x)²).
Rule1d gauss_lobatto(int n) {
  const int N = n - 1;
  Rule1d r{Eigen::VectorXd(n), Eigen::VectorXd(n)};
  for (int i = 0; i < n; ++i) {
    double x = -std::cos(M_PI * i / N), pn = 1.0;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1.0, p1 = x;
      for (int k = 2; k <= N; ++k) {
        const double p2 = ((2.0 * k - 1) * x * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      pn = p1;
      const double dx = (x * p1 - p0) / (n * p1);
      x -= dx;
      if (std::abs(dx) < 1e-16) break;
    }
    r.x(i) = (x + 1) / 2;
    r.w(i) = 1.0 / (N * n * pn * pn);  // 2/(n(n−1)P²) halved for [0, 1]
  }
  return r;
}

int points_for_degree(int degree) { return degree / 2 + 1; }  // Gauss: exact to 2n − 1

// The product of the n-point rule g on [0, 1] mapped to [−1, 1]^dim.
QuadratureRule tensor_rule(QuadratureRule q, const Rule1d& g, int n, int dim) {
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

QuadratureRule make_rule(ElementType type, int degree, QuadratureFamily family);

// Prism, Lobatto: the collapsed triangle ξ = s(1 − t), η = t with m Gauss–Lobatto points in s
// and m Gauss–Lobatto–Jacobi points of weight 1 − t in t (exact to 2m − 3 in both, so to
// total degree 2m − 3 in (ξ, η)), the m points at t = 1 joined at the corner (0, 1), times m
// Gauss–Lobatto points in ζ: the corners, edges and faces of the prism are among the points,
// where the μ barrier must act as on hexahedra (positive weights, not symmetric).
QuadratureRule lobatto_prism_rule(QuadratureRule q, int m) {
  const Rule1d s = gauss_lobatto(m), t = gauss_lobatto_jacobi(m), z = gauss_lobatto(m);
  const int n_tri = m * (m - 1) + 1;
  q.points.resize(3, n_tri * m);
  q.weights.resize(n_tri * m);
  for (int k = 0, p = 0; k < m; ++k)
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < (j + 1 < m ? m : 1); ++i, ++p) {
        const bool corner = j + 1 == m;  // t = 1: one point of weight Σ_i w_i = 1 times t's
        q.points.col(p) << (corner ? 0.0 : s.x(i) * (1 - t.x(j))), t.x(j), 2 * z.x(k) - 1;
        q.weights(p) = (corner ? 1.0 : s.w(i)) * t.w(j) * 2 * z.w(k);
      }
  return q;
}

// Prism: the triangle's rule of the same degree times n Gauss points in ζ. Pyramid: the
// collapse ξ = u(1 − ζ), η = v(1 − ζ) of the cube [−1, 1]² × [0, 1], Gauss in u and v and
// Gauss–Jacobi of weight (1 − ζ)² (the collapse's Jacobian) in ζ, with one point more in ζ,
// whose integrands gain the factors (1 − ζ) of ξ and η; exact for polynomials of degree
// `degree` in (u, v, ζ) and so for products of the rational P1 basis and its gradients.
QuadratureRule prism_or_pyramid_rule(QuadratureRule q, int n) {
  const auto g = gauss_jacobi(n, 0);
  if (q.type == ElementType::Prism) {
    const QuadratureRule tri = make_rule(ElementType::Triangle, q.degree, QuadratureFamily::Gauss);
    q.points.resize(3, tri.n_points() * n);
    q.weights.resize(tri.n_points() * n);
    for (int k = 0, p = 0; k < n; ++k)
      for (int i = 0; i < tri.n_points(); ++i, ++p) {
        q.points.col(p) << tri.points.col(i), 2 * g.x(k) - 1;
        q.weights(p) = tri.weights(i) * 2 * g.w(k);
      }
    return q;
  }
  const auto gz = gauss_jacobi(n + 1, 2);
  q.points.resize(3, n * n * (n + 1));
  q.weights.resize(n * n * (n + 1));
  for (int k = 0, p = 0; k <= n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i, ++p) {
        const double h = 1 - gz.x(k);
        q.points.col(p) << (2 * g.x(i) - 1) * h, (2 * g.x(j) - 1) * h, gz.x(k);
        q.weights(p) = 4 * g.w(i) * g.w(j) * gz.w(k);
      }
  return q;
}

QuadratureRule make_rule(ElementType type, int degree, QuadratureFamily family) {
  QuadratureRule q{type, degree, {}, {}};
  const int n = points_for_degree(std::max(degree, 0));
  const int dim = topological_dim(type);
  if (type == ElementType::Point) {
    q.points = Eigen::MatrixXd(0, 1);
    q.weights = Eigen::VectorXd::Ones(1);
    return q;
  }
  const int m_lobatto = std::max(2, (std::max(degree, 0) + 4) / 2);  // Lobatto: exact to 2m − 3
  if (type == ElementType::Prism && family == QuadratureFamily::Lobatto) return lobatto_prism_rule(q, m_lobatto);
  if (type == ElementType::Prism || type == ElementType::Pyramid) return prism_or_pyramid_rule(q, n);
  if (is_tensor(type) || type == ElementType::Line) {  // Gauss–Legendre (–Lobatto) on [−1, 1]^d
    const bool lobatto = family == QuadratureFamily::Lobatto;
    const int m = lobatto ? m_lobatto : n;
    const auto g = lobatto ? gauss_lobatto(m) : gauss_jacobi(m, 0);
    return tensor_rule(q, g, m, dim);
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

const QuadratureRule& quadrature_rule(ElementType type, int degree, QuadratureFamily family) {
  MESHMORPH_CHECK(degree >= 0 && degree <= 40, "quadrature degree out of range");
  if (!is_tensor(type) && type != ElementType::Line && type != ElementType::Prism)
    family = QuadratureFamily::Gauss;  // one rule per simplex and pyramid
  static std::mutex mutex;
  static std::map<std::tuple<ElementType, int, QuadratureFamily>, std::unique_ptr<QuadratureRule>> cache;
  std::lock_guard lock(mutex);
  auto& slot = cache[{type, degree, family}];
  if (!slot) slot = std::make_unique<QuadratureRule>(make_rule(type, degree, family));
  return *slot;
}

int metric_quadrature_degree(ElementType type, int order) {
  if (type == ElementType::Point) return 0;
  if (is_simplex(type)) return order == 1 && type != ElementType::Line ? 1 : 2 * order;
  return 2 * order + 1;  // tensor cells, prisms, pyramids
}

}  // namespace meshmorph
