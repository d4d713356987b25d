// SPDX-License-Identifier: MIT
#include "solve/detail/amg.h"

#include <set>

#include <gtest/gtest.h>

#include "solve/detail/cholmod_solver.h"
#include "solve/linear_solver_fixtures.h"

namespace meshmorph {
namespace {

TEST(AmgAggregates, CoverEveryNodeAndCoarsenByAFactorOfSeveral) {
  for (int dim : {2, 3}) {
    SCOPED_TRACE(dim);
    const Eigen::SparseMatrix<double> A = test::stiffness_matrix(dim, dim == 2 ? 24 : 8, true);
    int n_agg = 0;
    const std::vector<int> agg = detail::aggregate_nodes(detail::view_of(A), dim, 0.08, 1, n_agg);
    const int n_nodes = static_cast<int>(A.rows()) / dim;
    ASSERT_EQ(static_cast<int>(agg.size()), n_nodes);
    std::vector<int> size(static_cast<std::size_t>(n_agg), 0);
    for (int a : agg) {
      ASSERT_GE(a, 0);
      ASSERT_LT(a, n_agg);
      ++size[a];
    }
    for (int s : size) EXPECT_GE(s, 1);
    EXPECT_LE(n_agg, n_nodes / 4);
    EXPECT_GE(n_agg, n_nodes / 40);
  }
}

TEST(AmgAggregates, AreConnected) {
  const Eigen::SparseMatrix<double> A = test::stiffness_matrix(2, 16, false);
  int n_agg = 0;
  const std::vector<int> agg = detail::aggregate_nodes(detail::view_of(A), 2, 0.08, 1, n_agg);
  // Node adjacency from the matrix; every aggregate is a connected set of nodes.
  const int n_nodes = static_cast<int>(A.rows()) / 2;
  std::vector<std::set<int>> adjacent(static_cast<std::size_t>(n_nodes));
  for (int k = 0; k < A.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, k); it; ++it)
      adjacent[it.row() / 2].insert(static_cast<int>(it.col()) / 2);
  for (int a = 0; a < n_agg; ++a) {
    std::vector<int> members;
    for (int I = 0; I < n_nodes; ++I)
      if (agg[I] == a) members.push_back(I);
    std::set<int> reached{members.front()};
    for (bool grew = true; grew;) {
      grew = false;
      for (int I : members)
        if (!reached.count(I))
          for (int J : adjacent[I])
            if (reached.count(J)) {
              reached.insert(I);
              grew = true;
              break;
            }
    }
    EXPECT_EQ(reached.size(), members.size()) << "aggregate " << a << " is not connected";
  }
}

// CG needs a symmetric positive definite preconditioner: yᵀM⁻¹z = zᵀM⁻¹y and yᵀM⁻¹y > 0.
TEST(AmgHierarchy, VCycleIsSymmetricPositiveDefinite) {
  for (int dim : {2, 3}) {
    SCOPED_TRACE(dim);
    const Eigen::SparseMatrix<double> A =
        dim == 2 ? test::stiffness_matrix(2, 32, true, 10.0, 1.0) : test::energy_hessian<3>(1, 10);
    detail::AmgOptions options;
    options.block_size = dim;
    options.coarse_size = 50;
    detail::AmgHierarchy amg(options);
    ASSERT_TRUE(amg.setup(detail::view_of(A)));
    EXPECT_GE(amg.n_levels(), 3);
    EXPECT_LT(amg.operator_complexity(), 2.5);
    for (unsigned seed = 1; seed < 4; ++seed) {
      const Eigen::VectorXd y = test::random_vector(A.rows(), seed), z = test::random_vector(A.rows(), seed + 10);
      Eigen::VectorXd My(A.rows()), Mz(A.rows());
      amg.apply(y.data(), My.data());
      amg.apply(z.data(), Mz.data());
      EXPECT_NEAR(y.dot(Mz), z.dot(My), 1e-10 * y.norm() * Mz.norm());
      EXPECT_GT(y.dot(My), 0.0);
    }
  }
}

// One V-cycle as a stationary iteration x ← x + M⁻¹(b − Ax) contracts the error.
TEST(AmgHierarchy, VCycleContractsTheError) {
  const Eigen::SparseMatrix<double> A = test::stiffness_matrix(3, 12, false);
  detail::AmgOptions options;
  options.block_size = 3;
  options.coarse_size = 100;
  detail::AmgHierarchy amg(options);
  ASSERT_TRUE(amg.setup(detail::view_of(A)));
  const Eigen::VectorXd b = test::random_vector(A.rows());
  Eigen::VectorXd x = Eigen::VectorXd::Zero(A.rows()), c(A.rows());
  for (int it = 0; it < 10; ++it) {
    const Eigen::VectorXd r = b - A * x;
    amg.apply(r.data(), c.data());
    x += c;
  }
  EXPECT_LE((b - A * x).norm(), 1e-5 * b.norm());  // a rate below 0.3 per cycle
}

// The products that read a node's column indices once for all its rows: the same numbers,
// only for matrices whose nodes couple in whole blocks.
TEST(AmgCsr, BlockRowProductsMatchTheScalarOnes) {
  for (int dim : {2, 3}) {
    SCOPED_TRACE(dim);
    Eigen::SparseMatrix<double> A = test::stiffness_matrix(dim, 6, true);
    A.makeCompressed();
    const detail::SparseView view = detail::view_of(A);
    ASSERT_TRUE(detail::has_block_rows(view, dim));
    EXPECT_FALSE(detail::has_block_rows(view, 1));
    const Eigen::VectorXd x = test::random_vector(A.rows(), 3), b = test::random_vector(A.rows(), 4);
    Eigen::VectorXd y(A.rows()), z(A.rows());
    detail::spmv(view, dim, x.data(), y.data(), 2);
    EXPECT_LE((y - A * x).norm(), 1e-14 * (A * x).norm());
    detail::residual(view, dim, b.data(), x.data(), z.data(), 2);
    EXPECT_LE((z - (b - A * x)).norm(), 1e-14 * (b - A * x).norm());
    // One more entry in one row of a node: its rows no longer share a pattern.
    Eigen::SparseMatrix<double> B = A;
    B.coeffRef(0, B.cols() - 1) += 1.0;
    B.makeCompressed();
    EXPECT_FALSE(detail::has_block_rows(detail::view_of(B), dim));
  }
  // The block Laplacian couples only like components: its blocks are diagonal, not whole.
  Eigen::SparseMatrix<double> L = test::stiffness_matrix(3, 6, false);
  L.makeCompressed();
  EXPECT_FALSE(detail::has_block_rows(detail::view_of(L), 3));
}

TEST(AmgHierarchy, NonPositiveDiagonalIsNotPositiveDefinite) {
  Eigen::SparseMatrix<double> A = test::stiffness_matrix(2, 8, false);
  A.coeffRef(5, 5) = -1.0;
  detail::AmgHierarchy amg(detail::AmgOptions{});
  EXPECT_FALSE(amg.setup(detail::view_of(A)));
}

}  // namespace
}  // namespace meshmorph
