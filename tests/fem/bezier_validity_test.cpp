// SPDX-License-Identifier: MIT
#include "fem/detail/bezier_validity.h"

#include <cmath>
#include <cstdlib>
#include <limits>

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <gtest/gtest.h>

#include "meshmorph/fem/jacobian.h"
#include "meshmorph/fem/quadrature.h"
#include "meshmorph/fem/reference_element.h"
#include "meshmorph/fem/structured.h"
#include "meshmorph/fem/validity.h"
#include "support/element_cases.h"

namespace meshmorph {
namespace {

using test::ElementCase;

std::vector<ElementCase> curved_cases() {
  std::vector<ElementCase> out;
  for (const ElementCase& c : test::all_cell_cases())
    if (detail::det_needs_bounds(c.type, c.order)) out.push_back(c);
  return out;
}

int det_degree(const ElementCase& c) {
  const int d = topological_dim(c.type);
  return is_simplex(c.type) ? d * (c.order - 1) : d * c.order - 1;
}

double binomial(int n, int k) {
  double b = 1.0;
  for (int i = 1; i <= k; ++i) b = b * (n - k + i) / i;
  return b;
}

// Σ c_α B_α at a reference point (the unit simplex's coordinates, or [−1, 1]^d), written out
// from the definition of the Bernstein polynomials.
double bernstein_sum(const ElementCase& c, const Eigen::VectorXd& coefficients, const Eigen::VectorXd& xi) {
  const int q = det_degree(c), dim = topological_dim(c.type);
  const Eigen::MatrixXd alphas = (detail::unit_lattice(c.type, q) * q).array().round();
  double sum = 0.0;
  for (Eigen::Index a = 0; a < alphas.cols(); ++a) {
    double b = 1.0;
    if (is_simplex(c.type)) {
      int left = q;
      for (int k = 0; k < dim; ++k) {
        const int ak = static_cast<int>(alphas(k, a));
        b *= binomial(left, ak) * std::pow(xi(k), ak);
        left -= ak;
      }
      b *= std::pow(1.0 - xi.sum(), left);
    } else {
      for (int k = 0; k < dim; ++k) {
        const int ak = static_cast<int>(alphas(k, a));
        const double t = 0.5 * (xi(k) + 1.0);
        b *= binomial(q, ak) * std::pow(t, ak) * std::pow(1.0 - t, q - ak);
      }
    }
    sum += coefficients(a) * b;
  }
  return sum;
}

class BezierValidity : public ::testing::TestWithParam<ElementCase> {};

// The coefficients are those of det A: their Bernstein sum is det A at points off the lattice.
TEST_P(BezierValidity, CoefficientsSumToTheDeterminant) {
  const auto mesh = structured_mesh(GetParam().type, GetParam().order, 1);
  const auto& b = mesh.cells[0];
  std::srand(5);
  const Eigen::MatrixXd X = cell_coordinates(mesh, b, 0) + 0.2 * Eigen::MatrixXd::Random(mesh.dim, b.n_nodes_per_cell());
  const Eigen::VectorXd c = detail::det_bernstein_coefficients(b.type, b.order, X);
  Eigen::MatrixXd points = 0.5 * (Eigen::MatrixXd::Random(mesh.dim, 7).array() + 1.0);  // in the unit box
  if (is_simplex(b.type)) points = (points.array().rowwise() / (1.0 + points.colwise().sum().array())).matrix();
  else points = (2.0 * points.array() - 1.0).matrix();
  const ShapeTable t = tabulate(b.type, b.order, points);
  for (int p = 0; p < t.n_points(); ++p) {
    const double det = jacobian(X, t, p).determinant();
    EXPECT_NEAR(bernstein_sum(GetParam(), c, points.col(p)), det, 1e-12 * std::max(1.0, std::abs(det))) << "point " << p;
  }
}

// Valid cells whose first coefficients include some ≤ 0 are decided by subdivision: certified
// valid (the sampled value comes back) when det A stays clearly positive on a fine lattice,
// found invalid when det A dips below zero there. Counts both kinds so that the sweep shows it
// met them.
TEST_P(BezierValidity, SubdivisionDecidesWhatTheFirstCoefficientsCannot) {
  const auto mesh = structured_mesh(GetParam().type, GetParam().order, 1);
  const auto& b = mesh.cells[0];
  Eigen::MatrixXd fine = structured_mesh(b.type, 1, mesh.dim == 2 ? 24 : 12).x;
  if (!is_simplex(b.type)) fine = (2.0 * fine.array() - 1.0).matrix();
  const ShapeTable t = tabulate(b.type, b.order, fine);  // (simplices: the square's points outside bend no rule)
  std::srand(13);
  int certified = 0, refuted = 0;
  const double marker = 12345.0;
  for (int trial = 0; trial < 400; ++trial) {
    const double amplitude = 0.05 + 0.4 * (trial % 8) / 8.0;
    Eigen::MatrixXd X = cell_coordinates(mesh, b, 0) + amplitude * Eigen::MatrixXd::Random(mesh.dim, b.n_nodes_per_cell());
    if (mesh.dim == 3 && trial % 2) {  // twisted about the vertical axis by up to 126° over the cell's height
      const double twist = 2.2 * (trial % 16) / 16.0;
      for (Eigen::Index n = 0; n < X.cols(); ++n) {
        const Eigen::Vector3d x = X.col(n);
        const double a = twist * x(2), cx = x(0) - 0.5, cy = x(1) - 0.5;
        X.col(n) << 0.5 + std::cos(a) * cx - std::sin(a) * cy, 0.5 + std::sin(a) * cx + std::cos(a) * cy, x(2);
      }
    }
    if (detail::det_bernstein_coefficients(b.type, b.order, X).minCoeff() > 0.0) continue;
    double lowest = std::numeric_limits<double>::infinity(), largest = 0.0;
    for (int q = 0; q < t.n_points(); ++q) {
      if (is_simplex(b.type) && fine.col(q).sum() > 1.0 + 1e-12) continue;
      const double det = jacobian(X, t, q).determinant();
      lowest = std::min(lowest, det), largest = std::max(largest, det);
    }
    const double found = detail::bezier_min_det(b.type, b.order, X, marker);
    if (lowest > 0.01 * largest) {
      EXPECT_EQ(found, marker) << "trial " << trial << ": det A ≥ " << lowest << " on the fine lattice";
      ++certified;
    } else if (lowest < 0.0) {
      EXPECT_LE(found, 0.0) << "trial " << trial << ": det A = " << lowest << " on the fine lattice";
      ++refuted;
    }
  }
  EXPECT_GT(certified, 0) << "no valid cell needed subdivision: the sweep does not test it";
  EXPECT_GT(refuted, 0) << "no invalid cell among them: the sweep does not test refutation";
}

INSTANTIATE_TEST_SUITE_P(CurvedCells, BezierValidity, ::testing::ValuesIn(curved_cases()), test::CaseName());


// Prisms: the coefficients on the triangle × segment Bernstein basis sum to det A; a prism whose
// det A dips below zero between its samples along ζ (its top twisted against its base) is found.
TEST(BezierValidity, PrismCoefficientsSumToTheDeterminantAndCatchADip) {
  for (int order = 1; order <= max_order_of(ElementType::Prism); ++order) {
    const auto mesh = structured_mesh(ElementType::Prism, order, 1);
    const auto& b = mesh.cells[0];
    std::srand(7);
    const Eigen::MatrixXd X = cell_coordinates(mesh, b, 0) + 0.1 * Eigen::MatrixXd::Random(3, b.n_nodes_per_cell());
    const Eigen::VectorXd c = detail::prism_det_coefficients(order, X);
    const auto [qa, qb] = detail::prism_det_degrees(order);
    const Eigen::MatrixXd tri = detail::unit_lattice(ElementType::Triangle, qa) * qa;
    for (const Eigen::Vector3d& xi : {Eigen::Vector3d(0.2, 0.3, -0.4), Eigen::Vector3d(0.6, 0.1, 0.7)}) {
      double sum = 0.0;
      const double t = (xi(2) + 1) / 2;
      for (Eigen::Index a = 0; a < tri.cols(); ++a)
        for (int k = 0; k <= qb; ++k) {
          const int a1 = static_cast<int>(std::lround(tri(0, a))), a2 = static_cast<int>(std::lround(tri(1, a)));
          const double bt = binomial(qa, a1) * binomial(qa - a1, a2) * std::pow(xi(0), a1) * std::pow(xi(1), a2) *
                            std::pow(1 - xi(0) - xi(1), qa - a1 - a2);
          sum += c(a + tri.cols() * k) * bt * binomial(qb, k) * std::pow(t, k) * std::pow(1 - t, qb - k);
        }
      const ShapeTable s = tabulate(b.type, b.order, xi);
      EXPECT_NEAR(sum, Eigen::Matrix3d(jacobian(X, s, 0)).determinant(), 1e-12);
    }
  }
  // Base √10·T, top diag(−1.054, −2.108)·T (T the unit triangle): the cross-sections between
  // are (1 − t)√10 + t·a by (1 − t)√10 + t·b, so det A < 0 for t = (ζ + 1)/2 in (0.6, 0.75)
  // and > 0 at t = 0, ½, 1 and at the Gauss points: only the expansion sees the fold.
  Eigen::MatrixXd X = reference_element(ElementType::Prism, 1).nodes;
  const Eigen::Matrix2d M0 = std::sqrt(10.0) * Eigen::Matrix2d::Identity(), M1 = Eigen::Vector2d(-1.054, -2.108).asDiagonal();
  for (int i = 0; i < 6; ++i) X.block<2, 1>(0, i) = (i < 3 ? M0 : M1) * X.block<2, 1>(0, i);
  EXPECT_LE(min_jacobian_det(ElementType::Prism, 1, X), 0.0);
  std::vector<std::uint8_t> none(static_cast<std::size_t>(validity_samples(ElementType::Prism, 1).n_points()), 0);
  EXPECT_GT(min_jacobian_det(ElementType::Prism, 1, X, none), 0.0);  // the samples alone
  EXPECT_GT(min_jacobian_det(ElementType::Prism, 1, reference_element(ElementType::Prism, 1).nodes), 0.0);
}

// Pyramids: det A is bilinear in (ξ, η)/(1 − ζ), least at the base corners: the validity
// minimum equals pyramid_min_det, and a base corner pushed through the opposite side of the
// base is caught.
TEST(BezierValidity, PyramidMinimumIsAtTheBaseCorners) {
  std::srand(11);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::MatrixXd X = reference_element(ElementType::Pyramid, 1).nodes + 0.3 * Eigen::MatrixXd::Random(3, 5);
    const double corners = detail::pyramid_min_det(X);
    EXPECT_NEAR(min_jacobian_det(ElementType::Pyramid, 1, X), corners, 1e-12 * (1 + std::abs(corners)));
    // Nowhere inside below it: dense samples.
    const ShapeTable t = tabulate(ElementType::Pyramid, 1, Eigen::MatrixXd(quadrature_rule(ElementType::Pyramid, 12).points));
    for (int q = 0; q < t.n_points(); ++q) EXPECT_GE(Eigen::Matrix3d(jacobian(X, t, q)).determinant(), corners - 1e-12);
  }
  Eigen::MatrixXd X = reference_element(ElementType::Pyramid, 1).nodes;
  X.col(2) << -0.5, -0.5, 0.0;  // corner 2 folded past the diagonal 1–3
  EXPECT_LE(min_jacobian_det(ElementType::Pyramid, 1, X), 0.0);
}


// Quadratic pyramids: det A is a polynomial in the collapsed coordinates; random curved
// pyramids negative anywhere on a fine set of points are found invalid, and straight ones
// valid.
TEST(BezierValidity, NoFoldOfAQuadraticPyramidEscapesTheBounds) {
  const Eigen::MatrixXd& ref = reference_element(ElementType::Pyramid, 2).nodes;
  EXPECT_GT(min_jacobian_det(ElementType::Pyramid, 2, ref), 0.0);
  const ShapeTable fine = tabulate(ElementType::Pyramid, 2, Eigen::MatrixXd(quadrature_rule(ElementType::Pyramid, 16).points));
  std::srand(13);
  int folded = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const double amplitude = 0.05 + 0.3 * (trial % 10) / 10.0;
    const Eigen::MatrixXd X = ref + amplitude * Eigen::MatrixXd::Random(3, 14);
    double lowest = std::numeric_limits<double>::infinity();
    for (int q = 0; q < fine.n_points(); ++q) lowest = std::min(lowest, Eigen::Matrix3d(jacobian(X, fine, q)).determinant());
    if (lowest < 0.0) {
      ++folded;
      EXPECT_LE(min_jacobian_det(ElementType::Pyramid, 2, X), 0.0) << "trial " << trial;
    }
  }
  EXPECT_GT(folded, 0);
}

}  // namespace
}  // namespace meshmorph
