// SPDX-License-Identifier: MIT
#include "solve/detail/amg.h"

#include <random>
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

// A random rows × 3m matrix of whole dim×dim blocks, two per node row, as a prolongator is.
detail::Csr random_block_prolongator(int rows, int coarse_nodes, int dim, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::uniform_int_distribution<int> node(0, coarse_nodes - 1);
  detail::Csr P;
  P.rows = rows;
  P.cols = dim * coarse_nodes;
  for (int I = 0; I < rows / dim; ++I) {
    int a = node(rng), b = node(rng);
    if (a == b) b = (a + 1) % coarse_nodes;
    if (a > b) std::swap(a, b);
    for (int r = 0; r < dim; ++r) {
      for (int J : {a, b})
        for (int c = 0; c < dim; ++c) {
          P.idx.push_back(dim * J + c);
          P.val.push_back(u(rng));
        }
      P.ptr.push_back(static_cast<int>(P.idx.size()));
    }
  }
  return P;
}

// Products recomputed for new values of the same patterns: the values of a fresh product, by
// the scalar route and (all three matrices of whole blocks) the block route; fresh products
// by the block route as by the scalar one; the block products of prolongators as the scalar
// ones.
TEST(AmgCsr, ProductValuesOfKnownPatternsMatchAFreshProduct) {
  for (int dim : {2, 3}) {
    SCOPED_TRACE(dim);
    Eigen::SparseMatrix<double> A = test::stiffness_matrix(dim, 5, true);
    A.makeCompressed();
    const detail::SparseView view = detail::view_of(A);
    const detail::Csr P = random_block_prolongator(static_cast<int>(A.rows()), 7, dim, 5);
    ASSERT_TRUE(detail::has_block_rows(P, dim));
    detail::Csr AP = detail::multiply(view, P, 1, 2);
    const detail::Csr R = detail::transpose(P, 2);
    detail::Csr RAP = detail::multiply(R, AP, 1, 2);
    ASSERT_TRUE(detail::has_block_rows(AP, dim) && detail::has_block_rows(R, dim) && detail::has_block_rows(RAP, dim));
    // New values: A's rows scaled (its pattern kept), the fresh products of them.
    Eigen::SparseMatrix<double> B = A;
    for (Eigen::Index k = 0; k < B.nonZeros(); ++k) B.valuePtr()[k] *= 1.0 + 0.3 * std::sin(static_cast<double>(k));
    const detail::SparseView view_b = detail::view_of(B);
    const detail::Csr fresh_ap = detail::multiply(view_b, P, 1, 2);
    const detail::Csr fresh_rap = detail::multiply(R, fresh_ap, 1, 2);
    // The block route of a fresh product: the same pattern, the values to rounding.
    const detail::Csr block_ap = detail::multiply(view_b, P, dim, 2);
    const detail::Csr block_rap = detail::multiply(R, block_ap, dim, 2);
    ASSERT_EQ(block_ap.ptr, fresh_ap.ptr);
    ASSERT_EQ(block_ap.idx, fresh_ap.idx);
    ASSERT_EQ(block_rap.ptr, fresh_rap.ptr);
    ASSERT_EQ(block_rap.idx, fresh_rap.idx);
    for (std::size_t k = 0; k < block_ap.val.size(); ++k)
      EXPECT_NEAR(block_ap.val[k], fresh_ap.val[k], 1e-13 * (1 + std::abs(fresh_ap.val[k])));
    for (std::size_t k = 0; k < block_rap.val.size(); ++k)
      EXPECT_NEAR(block_rap.val[k], fresh_rap.val[k], 1e-13 * (1 + std::abs(fresh_rap.val[k])));
    for (int block : {1, dim}) {
      SCOPED_TRACE(block);
      detail::multiply_values(view_b, P, AP, block, 2);
      detail::multiply_values(R, AP, RAP, block, 2);
      ASSERT_EQ(AP.idx, fresh_ap.idx);
      ASSERT_EQ(RAP.idx, fresh_rap.idx);
      for (std::size_t k = 0; k < AP.val.size(); ++k) EXPECT_NEAR(AP.val[k], fresh_ap.val[k], 1e-13 * (1 + std::abs(fresh_ap.val[k])));
      for (std::size_t k = 0; k < RAP.val.size(); ++k)
        EXPECT_NEAR(RAP.val[k], fresh_rap.val[k], 1e-13 * (1 + std::abs(fresh_rap.val[k])));
    }
    const Eigen::VectorXd x = test::random_vector(P.cols, 7), y = test::random_vector(P.rows, 8);
    Eigen::VectorXd scalar(P.rows), blocked(P.rows), rs(R.rows), rb(R.rows);
    detail::spmv(P, x.data(), scalar.data(), 2);
    detail::spmv(P, dim, x.data(), blocked.data(), 2);
    EXPECT_LE((scalar - blocked).norm(), 1e-14 * scalar.norm());
    detail::spmv(R, y.data(), rs.data(), 2);
    detail::spmv(R, dim, y.data(), rb.data(), 2);
    EXPECT_LE((rs - rb).norm(), 1e-14 * rs.norm());
  }
}

// The coarse operator slice by slice (A P never whole) is the two products' operator to the
// last bit, on one thread and on two, by the scalar and the block route; with values_only it
// follows new values of A the same way.
TEST(AmgCsr, GalerkinSliceBySliceIsTheWholeProductExactly) {
  for (int dim : {2, 3}) {
    Eigen::SparseMatrix<double> A = test::stiffness_matrix(dim, 5, true);
    A.makeCompressed();
    Eigen::SparseMatrix<double> B = A;
    for (Eigen::Index k = 0; k < B.nonZeros(); ++k) B.valuePtr()[k] *= 1.0 + 0.3 * std::sin(static_cast<double>(k));
    const detail::Csr P = random_block_prolongator(static_cast<int>(A.rows()), 7, dim, 5);
    const detail::Csr R = detail::transpose(P, 2);
    const int row_block = detail::has_block_rows(detail::view_of(A), dim) ? dim : 1;
    ASSERT_EQ(row_block, dim);
    for (int block : {1, dim})
      for (int threads : {1, 2}) {
        SCOPED_TRACE(::testing::Message() << dim << "D, block " << block << ", " << threads << " threads");
        const detail::Csr whole = detail::multiply(R, detail::multiply(detail::view_of(A), P, row_block, 2), block, 2);
        detail::Csr C;
        std::vector<int> ap_blocks;
        ASSERT_TRUE(detail::galerkin(detail::view_of(A), P, R, row_block, block, C, ap_blocks, false, threads));
        EXPECT_EQ(C.ptr, whole.ptr);
        EXPECT_EQ(C.idx, whole.idx);
        EXPECT_EQ(C.val, whole.val);
        const detail::Csr next = detail::multiply(R, detail::multiply(detail::view_of(B), P, row_block, 2), block, 2);
        ASSERT_TRUE(detail::galerkin(detail::view_of(B), P, R, row_block, block, C, ap_blocks, true, threads));
        EXPECT_EQ(C.idx, next.idx);
        EXPECT_EQ(C.val, next.val);
        detail::Csr wrong = P;
        EXPECT_FALSE(detail::galerkin(detail::view_of(B), P, R, row_block, block, wrong, ap_blocks, true, threads));
        std::vector<int> none;
        EXPECT_FALSE(detail::galerkin(detail::view_of(B), P, R, row_block, block, C, none, true, threads));
      }
  }
}

// refresh() recomputes the coarse operators of a new matrix through the kept prolongators:
// right after setup() it changes nothing (the same V-cycle to rounding), and for a matrix
// whose rows near the boundary jumped by 1e6 (a penalty increase) CG needs the iterations of
// a fresh set-up, where the old coarse operators (rebind) cost several times more.
TEST(AmgHierarchy, RefreshGivesTheCoarseOperatorsOfTheNewMatrix) {
  const Eigen::SparseMatrix<double> A = test::energy_hessian<3>(1, 10);
  detail::AmgOptions options;
  options.block_size = 3;
  options.coarse_size = 50;

  detail::AmgHierarchy amg(options);
  ASSERT_TRUE(amg.setup(detail::view_of(A)));
  const Eigen::VectorXd r = test::random_vector(A.rows(), 9);
  Eigen::VectorXd before(A.rows()), after(A.rows());
  amg.apply(r.data(), before.data());
  ASSERT_TRUE(amg.refresh(detail::view_of(A)));
  amg.apply(r.data(), after.data());
  EXPECT_LE((before - after).norm(), 1e-12 * before.norm());

  Eigen::SparseMatrix<double> C = A;
  for (Eigen::Index i = 0; i < C.rows() / 4; ++i) C.coeffRef(i, i) *= 1e6;
  C.makeCompressed();
  const Eigen::VectorXd b = test::random_vector(C.rows(), 4);
  // PCG iterations to 1e-8 with the hierarchy as it is now.
  const auto iterations = [&](detail::AmgHierarchy& M) {
    Eigen::VectorXd x = Eigen::VectorXd::Zero(C.rows()), res = b, z(C.rows());
    M.apply(res.data(), z.data());
    Eigen::VectorXd p = z;
    double rz = res.dot(z);
    int it = 0;
    while (res.norm() > 1e-8 * b.norm() && it < 200) {
      const Eigen::VectorXd q = C * p;
      const double alpha = rz / p.dot(q);
      x += alpha * p;
      res -= alpha * q;
      M.apply(res.data(), z.data());
      const double rz_new = res.dot(z);
      p = z + (rz_new / rz) * p;
      rz = rz_new;
      ++it;
    }
    return it;
  };
  ASSERT_TRUE(amg.rebind(detail::view_of(C)));
  const int rebound = iterations(amg);
  ASSERT_TRUE(amg.refresh(detail::view_of(C)));
  const int refreshed = iterations(amg);
  detail::AmgHierarchy fresh(options);
  ASSERT_TRUE(fresh.setup(detail::view_of(C)));
  const int set_up = iterations(fresh);
  EXPECT_LE(refreshed, set_up + set_up / 2 + 2);
  EXPECT_GT(rebound, 2 * refreshed);
}

TEST(AmgHierarchy, NonPositiveDiagonalIsNotPositiveDefinite) {
  Eigen::SparseMatrix<double> A = test::stiffness_matrix(2, 8, false);
  A.coeffRef(5, 5) = -1.0;
  detail::AmgHierarchy amg(detail::AmgOptions{});
  EXPECT_FALSE(amg.setup(detail::view_of(A)));
}

}  // namespace
}  // namespace meshmorph
