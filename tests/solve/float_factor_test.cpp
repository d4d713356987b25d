// SPDX-License-Identifier: MIT
#include "solve/detail/float_factor.h"

#include <gtest/gtest.h>

#include "solve/detail/cholmod_header.h"
#include "solve/linear_solver_fixtures.h"

namespace meshmorph {
namespace {

// CHOLMOD's supernodal factor of A (fill-reducing permutation included), copied in single
// precision: its solve must be A⁻¹ to single precision, on a matrix whose supernodes have
// more than four columns (the blocked products) and rows below them (the scatter).
TEST(FloatFactor, SolvesWithCholmodsSupernodalFactorToSinglePrecision) {
  const Eigen::SparseMatrix<double> A = test::stiffness_matrix(3, 9, true, 2.0, 1.0);
  cholmod_common c;
  cholmod_start(&c);
  c.print = 0;
  c.supernodal = CHOLMOD_SUPERNODAL;
  cholmod_sparse S = detail::cholmod_header(detail::view_of(A));
  cholmod_factor* L = cholmod_analyze(&S, &c);
  ASSERT_NE(L, nullptr);
  ASSERT_TRUE(cholmod_factorize(&S, L, &c));
  ASSERT_TRUE(L->is_super);
  int widest = 0, with_rows_below = 0;
  const auto* super = static_cast<const int*>(L->super);
  const auto* pi = static_cast<const int*>(L->pi);
  for (std::size_t s = 0; s < L->nsuper; ++s) {
    widest = std::max(widest, super[s + 1] - super[s]);
    with_rows_below += pi[s + 1] - pi[s] > super[s + 1] - super[s];
  }
  EXPECT_GT(widest, 4);
  EXPECT_GT(with_rows_below, 10);

  detail::FloatFactor F;
  F.assign(static_cast<int>(L->n), static_cast<int>(L->nsuper), super, pi, static_cast<const int*>(L->px),
           static_cast<const int*>(L->s), static_cast<const double*>(L->x), static_cast<const int*>(L->Perm));
  const Eigen::VectorXd b = test::random_vector(A.rows());
  Eigen::VectorXd x(b.size());
  F.solve(b.data(), x.data());
  const double residual = (A * x - b).norm() / b.norm();
  EXPECT_LT(residual, 1e-5);
  EXPECT_GT(residual, 1e-12);  // the copy is single precision, not the factor itself
  // In place (b and x alias), the same result.
  Eigen::VectorXd y = b;
  F.solve(y.data(), y.data());
  EXPECT_EQ((y - x).norm(), 0.0);
  cholmod_free_factor(&L, &c);
  cholmod_finish(&c);
}

}  // namespace
}  // namespace meshmorph
