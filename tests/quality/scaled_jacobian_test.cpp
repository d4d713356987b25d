// SPDX-License-Identifier: MIT
#include "meshmorph/quality/scaled_jacobian.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "meshmorph/fem/reference_element.h"
#include "meshmorph/quality/element_quality.h"
#include "support/random_matrices.h"

namespace meshmorph {
namespace {

Eigen::MatrixXd corners(ElementType t) { return ideal_jacobian(t) * reference_element(t, 1).nodes; }

// Verdict's reference values (ecosystem.md §B.1: ideal = 1; the right isosceles triangle
// and the right-corner tetrahedron are the textbook √(2/3) and √2/2).
TEST(ScaledJacobian, VerdictValuesOfLinearCells) {
  EXPECT_NEAR(scaled_jacobian_linear(ElementType::Triangle, corners(ElementType::Triangle)), 1.0, 1e-15);
  EXPECT_NEAR(scaled_jacobian_linear(ElementType::Tetrahedron, corners(ElementType::Tetrahedron)), 1.0, 1e-15);
  EXPECT_NEAR(scaled_jacobian_linear(ElementType::Quadrilateral, corners(ElementType::Quadrilateral)), 1.0, 1e-15);
  EXPECT_NEAR(scaled_jacobian_linear(ElementType::Hexahedron, corners(ElementType::Hexahedron)), 1.0, 1e-15);

  Eigen::MatrixXd tri(2, 3);
  tri << 0, 1, 0, 0, 0, 1;
  EXPECT_NEAR(scaled_jacobian_linear(ElementType::Triangle, tri), std::sqrt(2.0 / 3.0), 1e-15);
  Eigen::MatrixXd tet(3, 4);
  tet << 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1;
  EXPECT_NEAR(scaled_jacobian_linear(ElementType::Tetrahedron, tet), std::sqrt(0.5), 1e-15);
  Eigen::MatrixXd rhombus(2, 4);  // 60° rhombus: every corner gives sin 60°
  rhombus << 0, 1, 1.5, 0.5, 0, 0, std::sqrt(0.75), std::sqrt(0.75);
  EXPECT_NEAR(scaled_jacobian_linear(ElementType::Quadrilateral, rhombus), std::sqrt(0.75), 1e-15);
  Eigen::MatrixXd trapezoid(2, 4);  // corners (2, 0) and (1, 1) have 45° angles: sin 45°
  trapezoid << 0, 2, 1, 0, 0, 0, 1, 1;
  EXPECT_NEAR(scaled_jacobian_linear(ElementType::Quadrilateral, trapezoid), std::sqrt(0.5), 1e-15);
  const Eigen::MatrixXd cube = corners(ElementType::Hexahedron);
  Eigen::Matrix3d shear = Eigen::Matrix3d::Identity();
  shear(0, 2) = 0.75;  // ζ edges lean by 0.75: det / lengths = 1/√(1 + 0.75²) = 0.8
  EXPECT_NEAR(scaled_jacobian_linear(ElementType::Hexahedron, shear * cube), 0.8, 1e-15);
}

TEST(ScaledJacobian, InvariantUnderSimilaritiesAndSignedUnderMirroring) {
  std::mt19937 rng(12);
  for (ElementType t : {ElementType::Triangle, ElementType::Quadrilateral, ElementType::Tetrahedron, ElementType::Hexahedron}) {
    const int d = topological_dim(t);
    Eigen::MatrixXd X = corners(t);
    X.row(0) += 0.5 * X.row(1);  // sheared: not ideal
    const double sj = scaled_jacobian_linear(t, X);
    EXPECT_LT(sj, 0.999) << name_of(t);
    const Eigen::MatrixXd R = d == 2 ? Eigen::MatrixXd(test::random_rotation<2>(rng)) : Eigen::MatrixXd(test::random_rotation<3>(rng));
    EXPECT_NEAR(scaled_jacobian_linear(t, 0.3 * R * X), sj, 1e-14) << name_of(t);
    Eigen::MatrixXd mirrored = X;
    mirrored.row(1) *= -1.0;
    EXPECT_NEAR(scaled_jacobian_linear(t, mirrored), -sj, 1e-14) << name_of(t);
  }
}

TEST(ScaledJacobian, StraightSidedHighOrderCellsMatchTheirLinearValue) {
  for (ElementType t : {ElementType::Triangle, ElementType::Quadrilateral, ElementType::Tetrahedron, ElementType::Hexahedron}) {
    const int d = topological_dim(t);
    Eigen::MatrixXd M = Eigen::MatrixXd::Identity(d, d);
    M(0, 1) = 0.5;
    M(d - 1, d - 1) = 0.6;
    const Eigen::MatrixXd W = M * ideal_jacobian(t);
    const double linear = scaled_jacobian_linear(t, W * reference_element(t, 1).nodes);
    for (int p = 2; p <= max_order_of(t); ++p) {
      EXPECT_NEAR(scaled_jacobian(t, p, W * reference_element(t, p).nodes), linear, 1e-13) << name_of(t) << p;
    }
  }
}

TEST(ScaledJacobian, CurvingACellLowersItsMinimum) {
  const ElementType t = ElementType::Quadrilateral;
  Eigen::MatrixXd X = reference_element(t, 2).nodes;  // the square [−1, 1]², value 1
  EXPECT_NEAR(scaled_jacobian(t, 2, X), 1.0, 1e-14);
  X(1, 4) += 0.5;  // bend the bottom edge (node 4 is its mid-node) inwards
  const double sj = scaled_jacobian(t, 2, X);
  EXPECT_LT(sj, 0.95);
  EXPECT_GT(sj, 0.0);
  X(1, 4) += 2.0;  // through the top: inverted somewhere
  EXPECT_LT(scaled_jacobian(t, 2, X), 0.0);
}

TEST(ScaledJacobian, DegenerateIsZeroAndNonFiniteIsNaN) {
  for (ElementType t : {ElementType::Triangle, ElementType::Quadrilateral, ElementType::Tetrahedron, ElementType::Hexahedron}) {
    const Eigen::MatrixXd X = Eigen::MatrixXd::Zero(topological_dim(t), n_corners_of(t));
    EXPECT_EQ(scaled_jacobian_linear(t, X), 0.0) << name_of(t);
    Eigen::MatrixXd Y = corners(t);
    Y(0, 1) = std::nan("");
    EXPECT_TRUE(std::isnan(scaled_jacobian_linear(t, Y))) << name_of(t);
  }
}


// Prisms and pyramids: 1 on the cells of equal edges; Verdict's values on a right unit wedge
// (√2/2 · 2/√3 at the corners on the hypotenuse) and on a pyramid of height ½ over the unit
// square; negative (wedge) or 0 (pyramid) when inverted; the P2 prism's sampled value on a
// straight cell equals the linear one.
TEST(ScaledJacobian, PrismAndPyramidAsVerdict) {
  for (const ElementType t : {ElementType::Prism, ElementType::Pyramid}) {
    const Eigen::MatrixXd ideal = ideal_jacobian(t) * reference_element(t, 1).nodes;
    EXPECT_NEAR(scaled_jacobian_linear(t, ideal), 1.0, 1e-14) << name_of(t);
    EXPECT_NEAR(scaled_jacobian(t, 1, 3.0 * ideal), 1.0, 1e-14) << name_of(t);
  }
  Eigen::MatrixXd right(3, 6);
  right << 0, 1, 0, 0, 1, 0, 0, 0, 1, 0, 0, 1, 0, 0, 0, 1, 1, 1;
  EXPECT_NEAR(scaled_jacobian_linear(ElementType::Prism, right), std::sqrt(0.5) * 2.0 / std::sqrt(3.0), 1e-14);
  Eigen::MatrixXd flipped = right;
  flipped.row(2) *= -1.0;
  EXPECT_NEAR(scaled_jacobian_linear(ElementType::Prism, flipped), -2.0 / std::sqrt(3.0), 1e-14);  // the right-angled corners
  // Pyramid over [0, 1]² of height h = ½: tetrahedron (0 1 2 4) has 6V = h, longest corner
  // product at corner 0 or 2: 1 · √2 · √(½ + h²) = √2 · 0.866…
  Eigen::MatrixXd pyr(3, 5);
  pyr << 0, 1, 1, 0, 0.5, 0, 0, 1, 1, 0.5, 0, 0, 0, 0, 0.5;
  const double tet = 0.5 * std::sqrt(2.0) / (std::sqrt(2.0) * std::sqrt(0.75));
  EXPECT_NEAR(scaled_jacobian_linear(ElementType::Pyramid, pyr), tet * std::sqrt(2.0), 1e-14);
  pyr(2, 4) = -0.5;
  EXPECT_EQ(scaled_jacobian_linear(ElementType::Pyramid, pyr), 0.0);
  const Eigen::Matrix3d W = ideal_jacobian(ElementType::Prism);
  EXPECT_NEAR(scaled_jacobian(ElementType::Prism, 2, W * reference_element(ElementType::Prism, 2).nodes), 1.0, 1e-13);
}

}  // namespace
}  // namespace meshmorph
