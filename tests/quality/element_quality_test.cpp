// SPDX-License-Identifier: MIT
#include "meshmorph/quality/element_quality.h"

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include <Eigen/LU>
#include <gtest/gtest.h>

#include "meshmorph/fem/reference_element.h"
#include "meshmorph/fem/validity.h"
#include "support/element_cases.h"
#include "support/random_matrices.h"

namespace meshmorph {
namespace {

// η₀(M) for a constant T = M: |M|²/(d·det M^{2/d}).
double eta0(const Eigen::MatrixXd& M) {
  const double d = static_cast<double>(M.rows());
  return M.squaredNorm() / (d * std::pow(M.determinant(), 2.0 / d));
}

class ElementQuality : public ::testing::TestWithParam<test::ElementCase> {
 protected:
  int dim() const { return topological_dim(GetParam().type); }
  // The ideal element: the reference nodes mapped by the ideal Jacobian.
  Eigen::MatrixXd ideal() const {
    return ideal_jacobian(GetParam().type) * reference_element(GetParam().type, GetParam().order).nodes;
  }
  // A valid, irregular and (for order ≥ 2) curved input element: the ideal one, sheared,
  // with every node moved at random by up to 3%/order of the element size.
  Eigen::MatrixXd input() const {
    std::mt19937 rng(42);
    const double a = 0.03 / GetParam().order;
    std::uniform_real_distribution<double> u(-a, a);
    Eigen::MatrixXd S = Eigen::MatrixXd::Identity(dim(), dim());
    S(0, 1) = 0.4;
    S(dim() - 1, dim() - 1) = 0.7;
    Eigen::MatrixXd X = S * ideal();
    for (Eigen::Index i = 0; i < X.size(); ++i) X(i) += u(rng);
    return X;
  }
  Eigen::MatrixXd map(const Eigen::MatrixXd& M, const Eigen::MatrixXd& X) const {
    Eigen::MatrixXd Y = M * X;
    Y.colwise() += Eigen::VectorXd::LinSpaced(dim(), 3.0, -2.0);  // a translation
    return Y;
  }
  Eigen::MatrixXd rotation(unsigned seed) const {
    std::mt19937 rng(seed);
    if (dim() == 2) return test::random_rotation<2>(rng);
    return test::random_rotation<3>(rng);
  }
  Eigen::MatrixXd general_affine() const {
    Eigen::MatrixXd M(dim(), dim());
    if (dim() == 2) M << 1.3, 0.4, -0.2, 0.8;
    else M << 1.3, 0.4, 0.1, -0.2, 0.8, 0.3, 0.05, -0.1, 1.6;
    return M;
  }
};

TEST_P(ElementQuality, IdealElementHasShapeQualityOne) {
  const auto [type, order] = GetParam();
  EXPECT_NEAR(element_quality(type, order, ideal(), nullptr), 1.0, 1e-12);
  EXPECT_NEAR(element_quality(type, order, map(7.5 * rotation(1), ideal()), nullptr), 1.0, 1e-12);
}

TEST_P(ElementQuality, ShapeQualityOfAnAffineImageOfTheIdealIsClosedForm) {
  const auto [type, order] = GetParam();
  const Eigen::MatrixXd M = general_affine();
  EXPECT_NEAR(element_quality(type, order, map(M, ideal()), nullptr), 1.0 / eta0(M), 1e-12);
}

TEST_P(ElementQuality, SimilarImagesOfTheInputHaveQualityOne) {
  const auto [type, order] = GetParam();
  const Eigen::MatrixXd X0 = input();
  ASSERT_GT(min_jacobian_det(type, order, X0), 0.0);
  EXPECT_NEAR(element_quality(type, order, X0, &X0), 1.0, 1e-12);
  for (double s : {0.01, 1.0, 40.0}) {
    EXPECT_NEAR(element_quality(type, order, map(s * rotation(3), X0), &X0), 1.0, 1e-12) << s;
  }
  // The irregular input is not ideal: its shape quality is below 1.
  EXPECT_LT(element_quality(type, order, X0, nullptr), 0.99);
}

TEST_P(ElementQuality, GeneralAffineImageOfTheInputIsClosedForm) {
  const auto [type, order] = GetParam();
  const Eigen::MatrixXd X0 = input();
  const Eigen::MatrixXd M = general_affine() * rotation(4);
  const double expected = 1.0 / eta0(M);
  EXPECT_LT(expected, 0.95);
  EXPECT_NEAR(element_quality(type, order, map(M, X0), &X0), expected, 1e-12);
  EXPECT_NEAR(element_distortion(type, order, map(M, X0), &X0), eta0(M), 1e-12);
}

TEST_P(ElementQuality, InvertedElementHasQualityZero) {
  const auto [type, order] = GetParam();
  const Eigen::MatrixXd X0 = input();
  Eigen::MatrixXd mirrored = X0;
  mirrored.row(0) *= -1.0;
  EXPECT_EQ(element_quality(type, order, mirrored, &X0), 0.0);
  EXPECT_EQ(element_quality(type, order, mirrored, nullptr), 0.0);
  if (order >= 2) {
    // Corners untouched, the first edge node thrown across the element: curved-inverted.
    Eigen::MatrixXd bent = X0;
    const Eigen::VectorXd centre = X0.leftCols(n_corners_of(type)).rowwise().mean();
    const int e = n_corners_of(type);
    bent.col(e) = centre + 4.0 * (centre - X0.col(e));
    ASSERT_LE(min_jacobian_det(type, order, bent), 0.0);
    EXPECT_EQ(element_quality(type, order, bent, &X0), 0.0);
    EXPECT_EQ(element_quality(type, order, bent, nullptr), 0.0);
  }
}

TEST_P(ElementQuality, NonFiniteCoordinatesGiveZero) {
  const auto [type, order] = GetParam();
  Eigen::MatrixXd X = ideal();
  X(0, 0) = std::nan("");
  EXPECT_EQ(element_quality(type, order, X, nullptr), 0.0);
}

INSTANTIATE_TEST_SUITE_P(AllTypesAndOrders, ElementQuality, ::testing::ValuesIn(test::all_cell_cases()),
                         test::CaseName());
INSTANTIATE_TEST_SUITE_P(PrismPyramid, ElementQuality, ::testing::ValuesIn(test::prism_pyramid_cases()), test::CaseName());

TEST(IdealJacobian, MapsTheReferenceToUnitEdgeRegularSimplices) {
  const Eigen::MatrixXd W = ideal_jacobian(ElementType::Tetrahedron);
  const Eigen::MatrixXd X = W * reference_element(ElementType::Tetrahedron, 1).nodes;
  for (int a = 0; a < 4; ++a)
    for (int b = a + 1; b < 4; ++b) EXPECT_NEAR((X.col(a) - X.col(b)).norm(), 1.0, 1e-15);
  EXPECT_GT(W.determinant(), 0.0);
  const Eigen::MatrixXd T = ideal_jacobian(ElementType::Triangle) * reference_element(ElementType::Triangle, 1).nodes;
  EXPECT_NEAR((T.col(1) - T.col(2)).norm(), 1.0, 1e-15);
}

}  // namespace
}  // namespace meshmorph
