// SPDX-License-Identifier: MIT
#include "meshmorph/fem/lagrange_basis.h"

#include <random>

#include <gtest/gtest.h>

#include "support/element_cases.h"

namespace meshmorph {
namespace {

using test::ElementCase;

class LagrangeBasisSweep : public ::testing::TestWithParam<ElementCase> {
 protected:
  // Random point inside the reference element.
  Eigen::VectorXd random_point(std::mt19937& rng) const {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const auto& b = lagrange_basis(GetParam().type, GetParam().order);
    Eigen::VectorXd xi(b.dim());
    if (is_simplex(GetParam().type)) {
      do {
        for (int k = 0; k < b.dim(); ++k) xi(k) = u(rng);
      } while (xi.sum() > 1.0);
    } else {
      for (int k = 0; k < b.dim(); ++k) xi(k) = 2 * u(rng) - 1;
    }
    return xi;
  }
};

TEST_P(LagrangeBasisSweep, IsKroneckerAtNodes) {
  const auto& b = lagrange_basis(GetParam().type, GetParam().order);
  for (int j = 0; j < b.n(); ++j) {
    const auto N = b.values(b.reference().nodes.col(j));
    for (int a = 0; a < b.n(); ++a) EXPECT_NEAR(N(a), a == j ? 1.0 : 0.0, 1e-11) << "node " << j << " basis " << a;
  }
}

TEST_P(LagrangeBasisSweep, PartitionOfUnityAtRandomPoints) {
  std::mt19937 rng(7);
  const auto& b = lagrange_basis(GetParam().type, GetParam().order);
  for (int trial = 0; trial < 10; ++trial) {
    const auto xi = random_point(rng);
    EXPECT_NEAR(b.values(xi).sum(), 1.0, 1e-12);
    EXPECT_LT(b.gradients(xi).colwise().sum().norm(), 1e-10);
  }
}

TEST_P(LagrangeBasisSweep, GradientsMatchCentralDifferences) {
  std::mt19937 rng(11);
  const auto& b = lagrange_basis(GetParam().type, GetParam().order);
  const double h = 1e-6;
  for (int trial = 0; trial < 5; ++trial) {
    const auto xi = random_point(rng);
    const auto G = b.gradients(xi);
    for (int k = 0; k < b.dim(); ++k) {
      Eigen::VectorXd e = Eigen::VectorXd::Zero(b.dim());
      e(k) = h;
      const Eigen::VectorXd fd = (b.values(xi + e) - b.values(xi - e)) / (2 * h);
      EXPECT_LT((fd - G.col(k)).norm(), 1e-7 * std::max(1.0, G.col(k).norm()));
    }
  }
}

// Central differences of the gradients are exact to rounding for these polynomials up to the
// h² term, ~1e-12 at h = 1e-6 relative to the rounding ~1e-10 / h of the difference quotient.
TEST_P(LagrangeBasisSweep, HessiansMatchDifferencesOfGradients) {
  std::mt19937 rng(12);
  const auto& b = lagrange_basis(GetParam().type, GetParam().order);
  const double h = 1e-6;
  const int d = b.dim();
  for (int trial = 0; trial < 5; ++trial) {
    const auto xi = random_point(rng);
    const Eigen::MatrixXd H = b.hessians(xi);
    for (int k = 0; k < d; ++k) {
      Eigen::VectorXd e = Eigen::VectorXd::Zero(d);
      e(k) = h;
      const Eigen::MatrixXd fd = (b.gradients(xi + e) - b.gradients(xi - e)) / (2 * h);
      for (int l = 0; l < d; ++l) {
        EXPECT_LT((fd.col(l) - H.col(k * d + l)).norm(), 1e-6 * std::max(1.0, H.col(k * d + l).norm()));
        EXPECT_EQ(H.col(k * d + l), H.col(l * d + k));
      }
    }
  }
}

// Interpolating a polynomial of the element's degree reproduces it exactly everywhere.
TEST_P(LagrangeBasisSweep, ReproducesPolynomialsOfItsDegree) {
  std::mt19937 rng(3);
  const auto& b = lagrange_basis(GetParam().type, GetParam().order);
  const int p = GetParam().order;
  const auto f = [&](const Eigen::VectorXd& x) {
    double v = 1.0 + 0.5 * std::pow(x(0), p) - 0.25 * x(1);
    if (b.dim() == 3) v += 0.3 * std::pow(x(2), p - 1) * x(1);
    return v;
  };
  Eigen::VectorXd nodal(b.n());
  for (int a = 0; a < b.n(); ++a) nodal(a) = f(b.reference().nodes.col(a));
  for (int trial = 0; trial < 10; ++trial) {
    const auto xi = random_point(rng);
    EXPECT_NEAR(b.values(xi).dot(nodal), f(xi), 1e-11);
  }
}

INSTANTIATE_TEST_SUITE_P(AllCells, LagrangeBasisSweep, ::testing::ValuesIn(test::all_cell_cases()), test::CaseName());
INSTANTIATE_TEST_SUITE_P(PrismPyramid, LagrangeBasisSweep, ::testing::ValuesIn(test::prism_pyramid_cases()), test::CaseName());

}  // namespace
}  // namespace meshmorph
