// SPDX-License-Identifier: MIT
#include "meshmorph/quality/scaled_jacobian.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <Eigen/Geometry>
#include <Eigen/LU>

#include "meshmorph/error.h"
#include "meshmorph/fem/jacobian.h"
#include "meshmorph/fem/validity.h"

namespace meshmorph {
namespace {

constexpr double kTiny = std::numeric_limits<double>::min();  // Verdict's VERDICT_DBL_MIN
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a(0) * b(1) - a(1) * b(0); }

// Triangle with edges a = x1 − x0, b = x2 − x0 (c = b − a): every corner has the same
// cross product 2A, so Verdict divides by the largest product of two edge lengths.
double triangle(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const double la = a.norm(), lb = b.norm(), lc = (b - a).norm();
  const double longest = std::max({la * lb, la * lc, lb * lc});
  if (!(longest >= kTiny)) return std::isnan(longest) ? kNaN : 0.0;
  return cross2(a, b) * (2.0 / std::sqrt(3.0)) / longest;
}

// Tetrahedron with edges a, b, c from corner 0: 6V √2 / (largest corner product of lengths).
double tetrahedron(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const double la = a.norm(), lb = b.norm(), lc = c.norm();
  const double lab = (b - a).norm(), lac = (c - a).norm(), lbc = (c - b).norm();
  const double longest = std::max({la * lb * lc, la * lab * lac, lb * lab * lbc, lc * lac * lbc});
  if (!(longest >= kTiny)) return std::isnan(longest) ? kNaN : 0.0;
  return a.dot(b.cross(c)) * std::sqrt(2.0) / longest;
}

double normalized_det(const Eigen::Matrix2d& A) {
  const double l = A.col(0).norm() * A.col(1).norm();
  if (!(l >= kTiny)) return std::isnan(l) ? kNaN : 0.0;
  return A.determinant() / l;
}

double normalized_det(const Eigen::Matrix3d& A) {
  const double l = A.col(0).norm() * A.col(1).norm() * A.col(2).norm();
  if (!(l >= kTiny)) return std::isnan(l) ? kNaN : 0.0;
  return A.determinant() / l;
}

// The minimum of a set of values, NaN if any is NaN.
struct NanMin {
  double m = std::numeric_limits<double>::infinity();
  void add(double v) { m = (std::isnan(v) || std::isnan(m)) ? kNaN : std::min(m, v); }
};

double quadrilateral(const Eigen::MatrixXd& X) {
  NanMin m;
  for (int i = 0; i < 4; ++i) {
    Eigen::Matrix2d E;
    E << X.col((i + 1) % 4) - X.col(i), X.col((i + 3) % 4) - X.col(i);
    m.add(normalized_det(E));
  }
  return m.m;
}

double hexahedron(const Eigen::MatrixXd& X) {
  NanMin m;
  // Corner i: the edges to its neighbours along ξ, η, ζ, ordered so the unit cube gives +1.
  for (int i = 0; i < 8; ++i) {
    const int j = i % 4;
    const bool top = i >= 4;
    const int a = top ? 4 + (j + 3) % 4 : (j + 1) % 4;
    const int b = top ? 4 + (j + 1) % 4 : (j + 3) % 4;
    const int c = top ? j : j + 4;
    Eigen::Matrix3d E;
    E << X.col(a) - X.col(i), X.col(b) - X.col(i), X.col(c) - X.col(i);
    m.add(normalized_det(E));
  }
  // Centre: Verdict's principal axes (sums of the four edges in each direction).
  Eigen::Matrix3d P;
  P.col(0) = X.col(1) - X.col(0) + X.col(2) - X.col(3) + X.col(5) - X.col(4) + X.col(6) - X.col(7);
  P.col(1) = X.col(3) - X.col(0) + X.col(2) - X.col(1) + X.col(7) - X.col(4) + X.col(6) - X.col(5);
  P.col(2) = X.col(4) - X.col(0) + X.col(5) - X.col(1) + X.col(6) - X.col(2) + X.col(7) - X.col(3);
  m.add(normalized_det(P));
  return m.m;
}

// Verdict's wedge_scaled_jacobian on Gmsh's node order (ParaView hands Verdict VTK's wedge with
// corners 0 ↔ 1 and 3 ↔ 4 swapped, a rotation of Gmsh's order, on which the formula is the same):
// at each corner, the edges along the base triangle (next, previous corner) and the vertical
// one, 2/√3 · det / (product of lengths), least over the six corners.
double prism(const Eigen::MatrixXd& X) {
  NanMin m;
  for (int i = 0; i < 6; ++i) {
    const int base = i < 3 ? 0 : 3, j = i - base, up = i < 3 ? i + 3 : i - 3;
    const int next = base + (j + 1) % 3, prev = base + (j + 2) % 3;
    Eigen::Matrix3d E;
    E << X.col(next) - X.col(i), X.col(prev) - X.col(i), X.col(up) - X.col(i);
    const double v = normalized_det(E);
    m.add((i < 3 ? v : -v) * 2.0 / std::sqrt(3.0));
  }
  return m.m;
}

// Verdict's pyramid_scaled_jacobian: the tetrahedra (0 1 2 4), (0 2 3 4), (0 1 3 4), (1 2 3 4),
// their least scaled Jacobian times √2 (1 on the pyramid of equal edges), 0 if it is ≤ 0, and
// values above 1 reflected (2 − q).
double pyramid(const Eigen::MatrixXd& X) {
  static constexpr int k_tets[4][3] = {{0, 1, 2}, {0, 2, 3}, {0, 1, 3}, {1, 2, 3}};
  NanMin m;
  for (const auto& t : k_tets)
    m.add(tetrahedron(X.col(t[1]) - X.col(t[0]), X.col(t[2]) - X.col(t[0]), X.col(4) - X.col(t[0])));
  if (std::isnan(m.m)) return kNaN;
  if (m.m <= 0.0) return 0.0;
  const double q = m.m * std::sqrt(2.0);
  return q < 1.0 ? q : 2.0 - q;
}

void check_shape(ElementType type, const Eigen::MatrixXd& M, Eigen::Index cols, const char* what) {
  const int d = topological_dim(type);
  MESHMORPH_CHECK(d >= 2, "scaled_jacobian: not a cell family");
  MESHMORPH_CHECK(M.rows() == d && M.cols() >= cols, std::string("scaled_jacobian: ") + what + " has the wrong shape");
}

}  // namespace

double scaled_jacobian_linear(ElementType type, const Eigen::MatrixXd& X) {
  check_shape(type, X, n_corners_of(type), "X");
  switch (type) {
    case ElementType::Triangle: return triangle(X.col(1) - X.col(0), X.col(2) - X.col(0));
    case ElementType::Quadrilateral: return quadrilateral(X);
    case ElementType::Tetrahedron: return tetrahedron(X.col(1) - X.col(0), X.col(2) - X.col(0), X.col(3) - X.col(0));
    case ElementType::Prism: return prism(X);
    case ElementType::Pyramid: return pyramid(X);
    default: return hexahedron(X);
  }
}

double scaled_jacobian_at(ElementType type, const Eigen::MatrixXd& A) {
  check_shape(type, A, topological_dim(type), "A");
  switch (type) {
    case ElementType::Triangle: return triangle(A.col(0), A.col(1));
    case ElementType::Quadrilateral: return normalized_det(Eigen::Matrix2d(A));
    case ElementType::Tetrahedron: return tetrahedron(A.col(0), A.col(1), A.col(2));
    case ElementType::Prism: return normalized_det(Eigen::Matrix3d(A)) * 2.0 / std::sqrt(3.0);  // as at a corner
    default: return normalized_det(Eigen::Matrix3d(A));
  }
}

double scaled_jacobian(ElementType type, int order, const Eigen::MatrixXd& X) {
  if (order == 1) return scaled_jacobian_linear(type, X);
  const ShapeTable& samples = validity_samples(type, order);
  MESHMORPH_CHECK(X.cols() == samples.n_nodes(), "scaled_jacobian: X has the wrong number of nodes");
  NanMin m;
  for (int q = 0; q < samples.n_points(); ++q) m.add(scaled_jacobian_at(type, jacobian(X, samples, q)));
  return m.m;
}

}  // namespace meshmorph
