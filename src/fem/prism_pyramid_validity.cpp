// SPDX-License-Identifier: MIT
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <vector>

#include <Eigen/LU>

#include "fem/detail/bezier_validity.h"
#include "fem/detail/pyramid_functions.h"
#include "meshmorph/fem/lagrange_basis.h"
#include "meshmorph/fem/shape_table.h"

namespace meshmorph::detail {
namespace {

// The inverse of the Bernstein polynomials of degree q on [0, 1] at the points i/q: lattice
// values → coefficients.
Eigen::MatrixXd segment_inverse(int q) { return segment_bernstein(q).inverse(); }

// The least det A that bisection finds, from `root`: det A at a piece's lattice (`dets`) ≤ 0
// anywhere is returned; pieces whose coefficients (`coefficients`) are all positive are
// valid; others are halved (`halves`), down to 18 halvings and 512 pieces, after which
// `sampled` stands.
template <class Cell, class Dets, class Coefficients, class Halves>
double bisected_min(const Cell& root, Dets dets, Coefficients coefficients, Halves halves, double sampled) {
  constexpr int k_max_depth = 18, k_budget = 512;
  std::vector<Cell> stack{root};
  for (int examined = 0; !stack.empty() && examined < k_budget; ++examined) {
    const Cell s = stack.back();
    stack.pop_back();
    const auto v = dets(s);
    if (v.minCoeff() <= 0.0) return v.minCoeff();
    if (coefficients(v).minCoeff() > 0.0 || s.depth >= k_max_depth) continue;
    for (const Cell& h : halves(s)) stack.push_back(h);
  }
  return sampled;
}

// The product lattice of a prism of order p and the inverses of the Bernstein polynomials'
// values there, on the triangle (degree qa) and on the segment (degree qb).
struct PrismExpansion {
  int qa = 0, qb = 0;
  Eigen::MatrixXd tri;        ///< 2 × n_tri: the triangle's lattice (unit triangle)
  Eigen::MatrixXd tri_inv;    ///< n_tri × n_tri: values → coefficients on the triangle
  Eigen::MatrixXd line_inv;   ///< (qb+1) × (qb+1): the same on the segment
  ShapeTable root;            ///< the basis at the whole prism's lattice (triangle index fastest)
};

std::unique_ptr<PrismExpansion> make_expansion(int order) {
  auto e = std::make_unique<PrismExpansion>();
  const auto [qa, qb] = prism_det_degrees(order);
  e->qa = qa;
  e->qb = qb;
  e->tri = unit_lattice(ElementType::Triangle, qa);
  const auto n = e->tri.cols();
  Eigen::MatrixXd M(n, n);
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index a = 0; a < n; ++a) {
      const int a1 = static_cast<int>(std::lround(e->tri(0, a) * qa)), a2 = static_cast<int>(std::lround(e->tri(1, a) * qa));
      const double l1 = e->tri(0, i), l2 = e->tri(1, i), l0 = 1.0 - l1 - l2;
      M(i, a) = binomial(qa, a1) * binomial(qa - a1, a2) * std::pow(l1, a1) * std::pow(l2, a2) * std::pow(l0, qa - a1 - a2);
    }
  e->tri_inv = M.inverse();
  e->line_inv = segment_inverse(qb);
  Eigen::MatrixXd points(3, n * (qb + 1));
  for (int k = 0; k <= qb; ++k)
    for (Eigen::Index i = 0; i < n; ++i) points.col(k * n + i) << e->tri.col(i), -1.0 + 2.0 * k / qb;
  e->root = tabulate(ElementType::Prism, order, points);
  return e;
}

const PrismExpansion& expansion(int order) {
  static std::mutex mutex;
  static std::map<int, std::unique_ptr<PrismExpansion>> cache;
  std::lock_guard lock(mutex);
  auto& slot = cache[order];
  if (!slot) slot = make_expansion(order);
  return *slot;
}

// A piece of the prism: a triangle (its corners as columns, unit-triangle coordinates) times
// [z0, z1] ⊂ [−1, 1].
struct Piece {
  Eigen::Matrix<double, 2, 3> tri;
  double z0 = -1.0, z1 = 1.0;
  int depth = 0;
};

// det A at the piece's lattice (triangle index fastest), NaN as −∞; the whole prism's from
// the tabulated basis, its pieces' from the basis evaluated there.
Eigen::MatrixXd piece_dets(const PrismExpansion& e, const LagrangeBasis& basis, const Eigen::MatrixXd& X, const Piece& s) {
  Eigen::MatrixXd v(e.tri.cols(), e.qb + 1);
  Eigen::Vector3d xi;
  for (int k = 0, p = 0; k <= e.qb; ++k)
    for (Eigen::Index i = 0; i < e.tri.cols(); ++i, ++p) {
      double det = 0.0;
      if (s.depth == 0) {
        det = Eigen::Matrix3d(X.lazyProduct(e.root.grad(p))).determinant();
      } else {
        const double l1 = e.tri(0, i), l2 = e.tri(1, i);
        xi.head<2>() = (1 - l1 - l2) * s.tri.col(0) + l1 * s.tri.col(1) + l2 * s.tri.col(2);
        xi(2) = s.z0 + (s.z1 - s.z0) * k / e.qb;
        det = Eigen::Matrix3d(X * basis.gradients(xi)).determinant();
      }
      v(i, k) = det > -std::numeric_limits<double>::infinity() ? det : -std::numeric_limits<double>::infinity();
    }
  return v;
}

Eigen::MatrixXd coefficients(const PrismExpansion& e, const Eigen::MatrixXd& v) {
  return e.tri_inv * v * e.line_inv.transpose();
}

std::array<Piece, 2> halves(const Piece& s) {
  std::array<Piece, 2> h{s, s};
  h[0].depth = h[1].depth = s.depth + 1;
  int a = 0, b = 1;
  double longest = -1.0;
  for (int i = 0; i < 3; ++i)
    for (int j = i + 1; j < 3; ++j)
      if (const double l = (s.tri.col(i) - s.tri.col(j)).norm(); l > longest) longest = l, a = i, b = j;
  if (longest >= (s.z1 - s.z0) / 2) {
    const Eigen::Vector2d mid = 0.5 * (s.tri.col(a) + s.tri.col(b));
    h[0].tri.col(b) = mid;
    h[1].tri.col(a) = mid;
  } else {
    h[0].z1 = h[1].z0 = 0.5 * (s.z0 + s.z1);
  }
  return h;
}

}  // namespace

std::array<int, 2> prism_det_degrees(int order) { return {3 * order - 2, 3 * order - 1}; }

Eigen::VectorXd prism_det_coefficients(int order, const Eigen::MatrixXd& X) {
  const PrismExpansion& e = expansion(order);
  Piece root;
  root.tri << 0, 1, 0, 0, 0, 1;
  const Eigen::MatrixXd c = coefficients(e, piece_dets(e, lagrange_basis(ElementType::Prism, order), X, root));
  return c.reshaped();
}

double prism_min_det(int order, const Eigen::MatrixXd& X, double sampled) {
  const PrismExpansion& e = expansion(order);
  const LagrangeBasis& basis = lagrange_basis(ElementType::Prism, order);
  Piece root;
  root.tri << 0, 1, 0, 0, 0, 1;
  return bisected_min(
      root, [&](const Piece& s) { return piece_dets(e, basis, X, s); },
      [&](const Eigen::MatrixXd& v) { return coefficients(e, v); }, halves, sampled);
}

namespace {

// det A of a pyramid of order p as a polynomial on the box (u, v, ζ) ∈ [−1, 1]² × [0, 1]:
// degrees 3p − 1 in u and v, 3(p − 1) in ζ (≥ 1); the inverses of the segments' Bernstein
// polynomials at their lattices, and the nodal basis' coefficients on the pyramidal functions.
struct PyramidExpansion {
  std::array<int, 3> q{};
  std::array<Eigen::MatrixXd, 3> inv;
  Eigen::MatrixXd nodal;  ///< n × n: N_a = Σ_m nodal(m, a) f_m
};

const PyramidExpansion& pyramid_expansion(int order) {
  static std::mutex mutex;
  static std::map<int, std::unique_ptr<PyramidExpansion>> cache;
  std::lock_guard lock(mutex);
  auto& slot = cache[order];
  if (!slot) {
    auto e = std::make_unique<PyramidExpansion>();
    e->q = {3 * order - 1, 3 * order - 1, std::max(1, 3 * (order - 1))};
    for (std::size_t k = 0; k < 3; ++k) e->inv[k] = segment_inverse(e->q[k]);
    const Eigen::MatrixXd& nodes = lagrange_basis(ElementType::Pyramid, order).reference().nodes;
    Eigen::MatrixXd V(nodes.cols(), nodes.cols());
    for (Eigen::Index b = 0; b < nodes.cols(); ++b) V.row(b) = pyramid_functions(order, nodes.col(b), 0).transpose();
    e->nodal = V.inverse();
    slot = std::move(e);
  }
  return *slot;
}

struct Box {
  Eigen::Vector3d lo{-1, -1, 0}, hi{1, 1, 1};
  int depth = 0;
};

// det A at the box's lattice (u fastest), NaN as −∞.
Eigen::VectorXd box_dets(const PyramidExpansion& e, int order, const Eigen::MatrixXd& X, const Box& b) {
  const int mu = e.q[0] + 1, mv = e.q[1] + 1, mz = e.q[2] + 1;
  const Eigen::MatrixXd XN = X * e.nodal.transpose();  // X N_a = (X nodalᵀ) f
  Eigen::VectorXd v(mu * mv * mz);
  for (int k = 0, p = 0; k < mz; ++k)
    for (int j = 0; j < mv; ++j)
      for (int i = 0; i < mu; ++i, ++p) {
        const Eigen::Vector3d t(double(i) / e.q[0], double(j) / e.q[1], double(k) / e.q[2]);
        const Eigen::Vector3d uvz = b.lo + t.cwiseProduct(b.hi - b.lo);
        const double det = Eigen::Matrix3d(XN * pyramid_collapsed_gradients(order, uvz)).determinant();
        v(p) = det > -std::numeric_limits<double>::infinity() ? det : -std::numeric_limits<double>::infinity();
      }
  return v;
}

// The tensor Bernstein coefficients of lattice values v, axis by axis.
Eigen::VectorXd box_coefficients(const PyramidExpansion& e, const Eigen::VectorXd& v) {
  Eigen::VectorXd c = v, next(v.size());
  Eigen::Index stride = 1;
  for (std::size_t axis = 0; axis < 3; ++axis) {
    const int m = e.q[axis] + 1;
    for (Eigen::Index base = 0; base < c.size(); ++base) {
      if ((base / stride) % m != 0) continue;
      for (int i = 0; i < m; ++i) {
        double sum = 0.0;
        for (int k = 0; k < m; ++k) sum += e.inv[axis](i, k) * c(base + k * stride);
        next(base + i * stride) = sum;
      }
    }
    c.swap(next);
    stride *= m;
  }
  return c;
}

}  // namespace

double pyramid_bounds_min_det(int order, const Eigen::MatrixXd& X, double sampled) {
  const PyramidExpansion& e = pyramid_expansion(order);
  // Halve the longest side (ζ counts double: the box is 2 × 2 × 1).
  const auto split = [](const Box& b) {
    Eigen::Index axis = 0;
    (b.hi - b.lo).cwiseProduct(Eigen::Vector3d(1, 1, 2)).maxCoeff(&axis);
    std::array<Box, 2> h{b, b};
    h[0].depth = h[1].depth = b.depth + 1;
    h[0].hi(axis) = h[1].lo(axis) = 0.5 * (b.lo(axis) + b.hi(axis));
    return h;
  };
  return bisected_min(
      Box{}, [&](const Box& b) { return box_dets(e, order, X, b); },
      [&](const Eigen::VectorXd& v) { return box_coefficients(e, v); }, split, sampled);
}

double pyramid_min_det(const Eigen::MatrixXd& X) {
  double lowest = std::numeric_limits<double>::infinity();
  const LagrangeBasis& basis = lagrange_basis(ElementType::Pyramid, 1);
  const auto& corners = basis.reference().nodes;
  for (int i = 0; i < 4; ++i) lowest = std::min(lowest, Eigen::Matrix3d(X * basis.gradients(corners.col(i))).determinant());
  return lowest;
}

}  // namespace meshmorph::detail
