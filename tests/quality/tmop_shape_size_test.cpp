// SPDX-License-Identifier: MIT
#include "meshmorph/quality/tmop_shape_size.h"

#include <cmath>
#include <random>
#include <stdexcept>

#include <gtest/gtest.h>

#include "meshmorph/quality/tmop_shape.h"
#include "support/random_matrices.h"

namespace meshmorph {
namespace {

TEST(TmopMu77, ClosedFormAtDiag21) {
  // τ = 2: ½(2 − ½)² = 9/8, in 2D and in 3D (diag(2, 1, 1)).
  EXPECT_DOUBLE_EQ(TmopMu77<2>().eval(Eigen::Vector2d(2, 1).asDiagonal().toDenseMatrix(), Want::Value).mu, 1.125);
  EXPECT_DOUBLE_EQ(TmopMu77<3>().eval(Eigen::Vector3d(2, 1, 1).asDiagonal().toDenseMatrix(), Want::Value).mu, 1.125);
}

TEST(TmopMu77, ZeroExactlyOnUnitDeterminant) {
  std::mt19937 rng(5);
  for (const auto& s : test::matrix_samples<3>(3, false)) {
    const MatT<3> T = s.T / std::cbrt(s.T.determinant());  // any shape, τ = 1
    EXPECT_NEAR(TmopMu77<3>().eval(T, Want::Value).mu, 0.0, 1e-12) << s.kind;
  }
  EXPECT_GT(TmopMu77<2>().eval(2.0 * test::random_rotation<2>(rng), Want::Value).mu, 0.0);
}

TEST(TmopMu80, ClosedFormAtDiag21) {
  // γ = ½: ½·¼ + ½·9/8 = 11/16.
  EXPECT_DOUBLE_EQ(TmopMu80<2>().eval(Eigen::Vector2d(2, 1).asDiagonal().toDenseMatrix(), Want::Value).mu, 0.6875);
}

TEST(TmopMu80, InterpolatesShapeAndSize) {
  for (const auto& s : test::matrix_samples<2>(2, false)) {
    const MetricEval<2> shape = TmopMu2().eval(s.T, Want::Hessian);
    const MetricEval<2> size = TmopMu77<2>().eval(s.T, Want::Hessian);
    const MetricEval<2> mix = TmopMu80<2>(0.3).eval(s.T, Want::Hessian);
    EXPECT_NEAR(mix.mu, 0.3 * shape.mu + 0.7 * size.mu, 1e-12 * (1 + std::abs(mix.mu)));
    EXPECT_LE((mix.d2mu_dT2 - 0.3 * shape.d2mu_dT2 - 0.7 * size.d2mu_dT2).norm(), 1e-12 * (1 + mix.d2mu_dT2.norm()));
  }
  for (const auto& s : test::matrix_samples<3>(2, false)) {
    EXPECT_NEAR(TmopMu80<3>(1.0).eval(s.T, Want::Value).mu, TmopMu303().eval(s.T, Want::Value).mu, 1e-9);
    EXPECT_NEAR(TmopMu80<3>(0.0).eval(s.T, Want::Value).mu, TmopMu77<3>().eval(s.T, Want::Value).mu, 1e-9);
  }
}

TEST(TmopMu80, ZeroExactlyOnRotations) {
  std::mt19937 rng(6);
  const MatT<3> R = test::random_rotation<3>(rng);
  EXPECT_NEAR(TmopMu80<3>().eval(R, Want::Value).mu, 0.0, 1e-14);
  EXPECT_GT(TmopMu80<3>().eval(1.1 * R, Want::Value).mu, 0.0);  // size matters
}

TEST(TmopMu80, RejectsGammaOutsideUnitInterval) {
  EXPECT_THROW(TmopMu80<2>(-0.1), std::invalid_argument);
  EXPECT_THROW(TmopMu80<3>(1.5), std::invalid_argument);
}

}  // namespace
}  // namespace meshmorph
