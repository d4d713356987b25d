// SPDX-License-Identifier: MIT
#include "meshmorph/fem/tensor_basis.h"

#include <gtest/gtest.h>

#include "meshmorph/fem/lagrange_basis.h"
#include "meshmorph/fem/shape_table.h"
#include "support/element_cases.h"

namespace meshmorph {
namespace {

class TensorBasisSweep : public ::testing::TestWithParam<test::ElementCase> {};

// N_a(ξ) = Π_k l_{i_k}(ξ_k) and its gradient from the 1D tables, against the nodal basis.
TEST_P(TensorBasisSweep, ProductsOfTheOneDimensionalBasisAreTheNodalBasis) {
  const auto [type, order] = GetParam();
  const TensorBasis& t = tensor_basis(type, order);
  if (is_simplex(type)) {
    EXPECT_EQ(t.P, 0);
    return;
  }
  const LagrangeBasis& basis = lagrange_basis(type, order);
  const int dim = basis.dim();
  ASSERT_EQ(t.P, order + 1);
  ASSERT_EQ(static_cast<int>(t.node.size()), basis.n());
  std::srand(3);
  for (int trial = 0; trial < 5; ++trial) {
    const Eigen::VectorXd xi = Eigen::VectorXd::Random(dim);
    Eigen::MatrixXd B[3], D[3];
    for (int k = 0; k < dim; ++k) t.tabulate({xi[k]}, B[k], D[k]);
    const Eigen::VectorXd N = basis.values(xi);
    const Eigen::MatrixXd G = basis.gradients(xi);
    for (int lattice = 0; lattice < basis.n(); ++lattice) {
      const int i[3] = {lattice % t.P, (lattice / t.P) % t.P, lattice / (t.P * t.P)};
      const int a = t.node[static_cast<std::size_t>(lattice)];
      double value = 1.0;
      for (int k = 0; k < dim; ++k) value *= B[k](0, i[k]);
      EXPECT_NEAR(value, N[a], 1e-12);
      for (int j = 0; j < dim; ++j) {
        double slope = 1.0;
        for (int k = 0; k < dim; ++k) slope *= (k == j ? D[k] : B[k])(0, i[k]);
        EXPECT_NEAR(slope, G(a, j), 1e-11);
      }
    }
  }
}

// Sum factorization over a table's grid is the dense product with its gradients: X ∇N for
// grid_gradients, R ∇Nᵀ for its transpose, on Gauss and Lobatto rules.
TEST_P(TensorBasisSweep, GridGradientsAreTheDenseProducts) {
  const auto [type, order] = GetParam();
  for (QuadratureFamily family : {QuadratureFamily::Gauss, QuadratureFamily::Lobatto}) {
    const ShapeTable& table = shape_table(type, order, 2 * order + 1, family);
    if (is_simplex(type)) {
      EXPECT_EQ(table.tensor, nullptr);
      continue;
    }
    ASSERT_NE(table.tensor, nullptr);
    const int dim = table.dim, n = table.n_nodes(), Q = table.n_points();
    std::srand(11);
    const Eigen::MatrixXd X = Eigen::MatrixXd::Random(dim, n), R = Eigen::MatrixXd::Random(dim, dim * Q);
    Eigen::MatrixXd G(dim, dim * Q), Y(dim, n);
    grid_gradients(*table.tensor, X.data(), dim, G.data());
    grid_gradients_transpose(*table.tensor, R.data(), dim, Y.data());
    EXPECT_LT((G - X * table.dN).cwiseAbs().maxCoeff(), 1e-12);
    EXPECT_LT((Y - R * table.dN.transpose()).cwiseAbs().maxCoeff(), 1e-12);
  }
}

INSTANTIATE_TEST_SUITE_P(AllCells, TensorBasisSweep, ::testing::ValuesIn(test::all_cell_cases()), test::CaseName());

}  // namespace
}  // namespace meshmorph
