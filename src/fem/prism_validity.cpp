// SPDX-License-Identifier: MIT
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <vector>

#include <Eigen/LU>

#include "fem/detail/bezier_validity.h"
#include "meshmorph/fem/lagrange_basis.h"

namespace meshmorph::detail {
namespace {

double binomial(int n, int k) {
  double b = 1.0;
  for (int i = 1; i <= k; ++i) b = b * (n - k + i) / i;
  return b;
}

// The product lattice of a prism of order p and the inverses of the Bernstein polynomials'
// values there, on the triangle (degree qa) and on the segment (degree qb).
struct PrismExpansion {
  int qa = 0, qb = 0;
  Eigen::MatrixXd tri;        ///< 2 × n_tri: the triangle's lattice (unit triangle)
  Eigen::MatrixXd tri_inv;    ///< n_tri × n_tri: values → coefficients on the triangle
  Eigen::MatrixXd line_inv;   ///< (qb+1) × (qb+1): the same on the segment
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
  Eigen::MatrixXd L(qb + 1, qb + 1);
  for (int i = 0; i <= qb; ++i)
    for (int k = 0; k <= qb; ++k) L(i, k) = binomial(qb, k) * std::pow(double(i) / qb, k) * std::pow(1.0 - double(i) / qb, qb - k);
  e->line_inv = L.inverse();
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

// det A at the piece's lattice (triangle index fastest), NaN as −∞.
Eigen::MatrixXd piece_dets(const PrismExpansion& e, const LagrangeBasis& basis, const Eigen::MatrixXd& X, const Piece& s) {
  Eigen::MatrixXd v(e.tri.cols(), e.qb + 1);
  Eigen::Vector3d xi;
  for (int k = 0; k <= e.qb; ++k)
    for (Eigen::Index i = 0; i < e.tri.cols(); ++i) {
      const double l1 = e.tri(0, i), l2 = e.tri(1, i);
      xi.head<2>() = (1 - l1 - l2) * s.tri.col(0) + l1 * s.tri.col(1) + l2 * s.tri.col(2);
      xi(2) = s.z0 + (s.z1 - s.z0) * k / e.qb;
      const double det = Eigen::Matrix3d(X * basis.gradients(xi)).determinant();
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
  constexpr int k_max_depth = 18, k_budget = 512;
  Piece root;
  root.tri << 0, 1, 0, 0, 0, 1;
  std::vector<Piece> stack{root};
  for (int examined = 0; !stack.empty() && examined < k_budget; ++examined) {
    const Piece s = stack.back();
    stack.pop_back();
    const Eigen::MatrixXd v = piece_dets(e, basis, X, s);
    if (v.minCoeff() <= 0.0) return v.minCoeff();
    if (coefficients(e, v).minCoeff() > 0.0 || s.depth >= k_max_depth) continue;
    for (const Piece& h : halves(s)) stack.push_back(h);
  }
  return sampled;
}

double pyramid_min_det(const Eigen::MatrixXd& X) {
  double lowest = std::numeric_limits<double>::infinity();
  const LagrangeBasis& basis = lagrange_basis(ElementType::Pyramid, 1);
  const auto& corners = basis.reference().nodes;
  for (int i = 0; i < 4; ++i) lowest = std::min(lowest, Eigen::Matrix3d(X * basis.gradients(corners.col(i))).determinant());
  return lowest;
}

}  // namespace meshmorph::detail
