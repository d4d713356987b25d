// SPDX-License-Identifier: MIT
#include "meshmorph/quality/distortion.h"

#include <cmath>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "support/random_matrices.h"

namespace meshmorph {
namespace {

TEST(Distortion, ClosedFormAtDiag21) {
  // 2D: |T|²/(2τ) = 5/4; 3D diag(2,1,1): 6/(3·2^{2/3}) = 2^{1/3}.
  const MatT<2> T2 = Eigen::Vector2d(2, 1).asDiagonal();
  const MatT<3> T3 = Eigen::Vector3d(2, 1, 1).asDiagonal();
  EXPECT_DOUBLE_EQ(Distortion<2>().eval(T2, Want::Value).mu, 1.25);
  EXPECT_DOUBLE_EQ(DistortionSquared<2>().eval(T2, Want::Value).mu, 1.5625);
  EXPECT_NEAR(Distortion<3>().eval(T3, Want::Value).mu, std::cbrt(2.0), 1e-15);
  EXPECT_NEAR(DistortionSquared<3>().eval(T3, Want::Value).mu, std::cbrt(4.0), 1e-15);
}

TEST(Distortion, OneExactlyOnSimilaritiesAndAboveOtherwise) {
  std::mt19937 rng(8);
  for (double s : {1e-4, 1.0, 250.0}) {
    EXPECT_NEAR(Distortion<2>().eval(s * test::random_rotation<2>(rng), Want::Value).mu, 1.0, 1e-14);
    EXPECT_NEAR(Distortion<3>().eval(s * test::random_rotation<3>(rng), Want::Value).mu, 1.0, 1e-14);
    EXPECT_NEAR(DistortionSquared<3>().eval(s * test::random_rotation<3>(rng), Want::Value).mu, 1.0, 1e-14);
  }
  for (const auto& s : test::matrix_samples<3>(3, false)) {
    EXPECT_GT(Distortion<3>().eval(s.T, Want::Value).mu, 1.0 + 1e-6) << s.kind;
  }
}

TEST(Distortion, InvariantUnderRotationsAndScaling) {
  std::mt19937 rng(9);
  for (const auto& s : test::matrix_samples<3>(3, false)) {
    if (s.kind == "near_singular") continue;
    const double eta = Distortion<3>().eval(s.T, Want::Value).mu;
    const MatT<3> R = test::random_rotation<3>(rng);
    EXPECT_NEAR(Distortion<3>().eval(R * s.T * R.transpose(), Want::Value).mu, eta, 1e-12 * eta);
    EXPECT_NEAR(Distortion<3>().eval(1e3 * s.T, Want::Value).mu, eta, 1e-12 * eta);
  }
}

TEST(Distortion, InfiniteForNonPositiveDeterminant) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(Distortion<2>().eval(Eigen::Vector2d(1, -1).asDiagonal().toDenseMatrix(), Want::Hessian).mu, inf);
  EXPECT_EQ(DistortionSquared<3>().eval(Eigen::Vector3d(1, 1, 0).asDiagonal().toDenseMatrix(), Want::Hessian).mu, inf);
}

}  // namespace
}  // namespace meshmorph
