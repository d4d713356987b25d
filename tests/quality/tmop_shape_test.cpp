// SPDX-License-Identifier: MIT
#include "meshmorph/quality/tmop_shape.h"

#include <cmath>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "support/random_matrices.h"

namespace meshmorph {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

TEST(TmopMu2, ClosedFormAtDiag21) {
  // |T|² = 5, τ = 2: 5/4 − 1.
  EXPECT_DOUBLE_EQ(TmopMu2().eval(Eigen::Vector2d(2, 1).asDiagonal().toDenseMatrix(), Want::Value).mu, 0.25);
}

TEST(TmopMu303, ClosedFormAtDiag211) {
  // |T|² = 6, τ = 2: 6/(3·2^{2/3}) − 1 = 2^{1/3} − 1.
  const MatT<3> T = Eigen::Vector3d(2, 1, 1).asDiagonal();
  EXPECT_NEAR(TmopMu303().eval(T, Want::Value).mu, std::cbrt(2.0) - 1.0, 1e-15);
}

TEST(TmopMu2, ZeroOnSimilarities) {
  std::mt19937 rng(1);
  for (double s : {1e-3, 0.5, 1.0, 7.0, 1e3}) {
    const MatT<2> T = s * test::random_rotation<2>(rng);
    const MetricEval<2> e = TmopMu2().eval(T, Want::Gradient);
    EXPECT_NEAR(e.mu, 0.0, 1e-14);
    EXPECT_LE(e.dmu_dT.norm() * s, 1e-13);  // a minimum: zero gradient (scaled by |T|)
  }
}

TEST(TmopMu303, ZeroOnSimilarities) {
  std::mt19937 rng(2);
  for (double s : {1e-3, 0.5, 1.0, 7.0, 1e3}) {
    const MatT<3> T = s * test::random_rotation<3>(rng);
    const MetricEval<3> e = TmopMu303().eval(T, Want::Gradient);
    EXPECT_NEAR(e.mu, 0.0, 1e-14);
    EXPECT_LE(e.dmu_dT.norm() * s, 1e-13);
  }
}

TEST(TmopMu2, InvariantUnderRotationsAndScaling) {
  std::mt19937 rng(3);
  for (const auto& s : test::matrix_samples<2>(3, false)) {
    if (s.kind == "near_singular") continue;
    const double mu = TmopMu2().eval(s.T, Want::Value).mu;
    const MatT<2> R = test::random_rotation<2>(rng);
    EXPECT_NEAR(TmopMu2().eval(R * s.T, Want::Value).mu, mu, 1e-12 * (1 + mu));
    EXPECT_NEAR(TmopMu2().eval(s.T * R, Want::Value).mu, mu, 1e-12 * (1 + mu));
    EXPECT_NEAR(TmopMu2().eval(3.7 * s.T, Want::Value).mu, mu, 1e-12 * (1 + mu));
    EXPECT_GT(mu, 0.0);
  }
}

TEST(TmopMu303, InvariantUnderRotationsAndScaling) {
  std::mt19937 rng(4);
  for (const auto& s : test::matrix_samples<3>(3, false)) {
    if (s.kind == "near_singular") continue;
    const double mu = TmopMu303().eval(s.T, Want::Value).mu;
    const MatT<3> R = test::random_rotation<3>(rng);
    EXPECT_NEAR(TmopMu303().eval(R * s.T, Want::Value).mu, mu, 1e-12 * (1 + mu));
    EXPECT_NEAR(TmopMu303().eval(s.T * R, Want::Value).mu, mu, 1e-12 * (1 + mu));
    EXPECT_NEAR(TmopMu303().eval(0.2 * s.T, Want::Value).mu, mu, 1e-12 * (1 + mu));
    EXPECT_GT(mu, 0.0);
  }
}

TEST(TmopMu2, InfiniteForNonPositiveDeterminant) {
  EXPECT_EQ(TmopMu2().eval(Eigen::Vector2d(-1, 1).asDiagonal().toDenseMatrix(), Want::Hessian).mu, kInf);
  EXPECT_EQ(TmopMu2().eval(Eigen::Vector2d(1, 0).asDiagonal().toDenseMatrix(), Want::Hessian).mu, kInf);
  EXPECT_EQ(TmopMu303().eval(Eigen::Vector3d(1, 1, -1).asDiagonal().toDenseMatrix(), Want::Value).mu, kInf);
  EXPECT_EQ(TmopMu303().eval(MatT<3>::Zero(), Want::Value).mu, kInf);
}

}  // namespace
}  // namespace meshmorph
