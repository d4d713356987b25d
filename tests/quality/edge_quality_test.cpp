// SPDX-License-Identifier: MIT
#include "meshmorph/quality/edge_quality.h"

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>

#include <gtest/gtest.h>

#include "meshmorph/quality/distortion.h"
#include "support/random_matrices.h"

namespace meshmorph {
namespace {

TEST(EdgeQuality, OneOnTheRegularSimplexAndItsSimilarities) {
  std::mt19937 rng(10);
  for (double s : {0.01, 1.0, 30.0}) {
    EXPECT_NEAR(EdgeQuality<2>().eval(s * test::random_rotation<2>(rng), Want::Value).mu, 1.0, 1e-14);
    EXPECT_NEAR(EdgeQuality<3>().eval(s * test::random_rotation<3>(rng), Want::Value).mu, 1.0, 1e-14);
  }
}

TEST(EdgeQuality, ClosedFormAtDiag21) {
  // Regular triangle edges (1,0), (½,√3/2), (−½,√3/2) under diag(2,1): Σl² = 4 + 7/4 + 7/4;
  // V = 2·√3/4; q* = 4√3 V / Σl² = 0.8; F = q*⁻¹ = 1.25 (= |T|²/(2τ): in 2D with δ = 0 and
  // n = −1 the edge quality equals the distortion, because Σ eⱼeⱼᵀ = (3/2) I).
  EXPECT_NEAR(EdgeQuality<2>().eval(Eigen::Vector2d(2, 1).asDiagonal().toDenseMatrix(), Want::Value).mu, 1.25, 1e-14);
  // n = −2 squares it.
  EXPECT_NEAR(EdgeQuality<2>({0.0, -2.0}).eval(Eigen::Vector2d(2, 1).asDiagonal().toDenseMatrix(), Want::Value).mu,
              1.5625, 1e-14);
}

TEST(EdgeQuality, EqualsDistortionIn2DWithoutRegularization) {
  for (const auto& s : test::matrix_samples<2>(3, false)) {
    const MetricEval<2> a = EdgeQuality<2>().eval(s.T, Want::Hessian);
    const MetricEval<2> b = Distortion<2>().eval(s.T, Want::Hessian);
    EXPECT_NEAR(a.mu, b.mu, 1e-9 * b.mu) << s.kind;
    EXPECT_LE((a.dmu_dT - b.dmu_dT).norm(), 1e-8 * b.dmu_dT.norm()) << s.kind;
  }
}

TEST(EdgeQuality, RegularizedVolumeAtTheIdentity) {
  // T = I, tet: q* = h(V_reg)/V_reg, h(V) = ½(V + √(V² + 4δ²)).
  const double v = std::sqrt(2.0) / 12.0, delta = 0.05;
  const double h = 0.5 * (v + std::sqrt(v * v + 4 * delta * delta));
  EXPECT_NEAR(EdgeQuality<3>({delta, -1.0}).eval(MatT<3>::Identity(), Want::Value).mu, v / h, 1e-14);
}

TEST(EdgeQuality, FiniteAndDecreasingThroughInversionWhenRegularized) {
  // Squash the regular triangle through zero area: F stays finite and grows as V decreases.
  const EdgeQuality<2> metric({0.01, -1.0});
  double previous = 0.0;
  for (double t : {1.0, 0.5, 0.1, 0.0, -0.1, -0.5}) {
    const double F = metric.eval(Eigen::Vector2d(1, t).asDiagonal().toDenseMatrix(), Want::Value).mu;
    EXPECT_TRUE(std::isfinite(F)) << t;
    EXPECT_GT(F, previous) << t;
    previous = F;
  }
  EXPECT_EQ(EdgeQuality<2>().eval(Eigen::Vector2d(1, -0.1).asDiagonal().toDenseMatrix(), Want::Value).mu,
            std::numeric_limits<double>::infinity());
}

// ∂F/∂δ, ∂²F/∂δ² against differences in δ, and the mixed derivative against the difference
// of ∂F/∂δ along T + t dT, at well-shaped, anisotropic and inverted T (paper 001 eq. 13).
template <int d>
void check_delta_derivatives() {
  std::mt19937 rng(7);
  std::normal_distribution<double> normal(0.0, 1.0);
  for (const auto& sample : test::matrix_samples<d>(3, true)) {
    if (sample.kind == "near_singular") continue;  // δ ≈ V there: covered by the inverted ones
    MatT<d> dT;
    for (int i = 0; i < d * d; ++i) dT(i) = normal(rng);
    const double scale = std::pow(std::abs(sample.T.determinant()), 1.0 / d);
    for (double delta : {0.05, 0.3}) {
      const double dl = delta * scale * scale;  // δ comparable with V
      const auto F = [&](double delta_, const MatT<d>& T) { return EdgeQuality<d>({delta_, -1.0}).eval(T, Want::Value).mu; };
      const auto D = [&](double delta_, const MatT<d>& T) { return EdgeQuality<d>({delta_, -1.0}).delta_derivatives(T, dT); };
      const typename EdgeQuality<d>::DeltaDerivatives a = D(dl, sample.T);
      const double h = 1e-3 * dl;
      const double fd1 = (F(dl - 2 * h, sample.T) - 8 * F(dl - h, sample.T) + 8 * F(dl + h, sample.T) - F(dl + 2 * h, sample.T)) / (12 * h);
      const double fd2 = (D(dl - 2 * h, sample.T).d_delta - 8 * D(dl - h, sample.T).d_delta + 8 * D(dl + h, sample.T).d_delta -
                          D(dl + 2 * h, sample.T).d_delta) / (12 * h);
      // Step below the smallest singular value (|τ|/|T|^{d−1} ≤ σ_min), where F varies fastest.
      const double t = 1e-3 * std::abs(sample.T.determinant()) / std::pow(sample.T.norm(), d - 1) / dT.norm();
      const auto along = [&](double s) { return D(dl, sample.T + s * dT).d_delta; };
      const double fdm = (along(-2 * t) - 8 * along(-t) + 8 * along(t) - along(2 * t)) / (12 * t);
      EXPECT_NEAR(a.d_delta, fd1, 1e-7 * std::max(1.0, std::abs(fd1))) << sample.kind << " δ " << dl;
      EXPECT_NEAR(a.d2_delta, fd2, 1e-6 * std::max(1.0, std::abs(fd2))) << sample.kind << " δ " << dl;
      EXPECT_NEAR(a.d2_delta_dT, fdm, 1e-6 * std::max(1.0, std::abs(fdm))) << sample.kind << " δ " << dl;
      EXPECT_LT(a.d_delta, 0.0) << "a larger δ lowers F";
    }
  }
}

TEST(EdgeQuality, DeltaDerivativesMatchDifferences2D) { check_delta_derivatives<2>(); }
TEST(EdgeQuality, DeltaDerivativesMatchDifferences3D) { check_delta_derivatives<3>(); }

TEST(EdgeQuality, RejectsBadParameters) {
  EXPECT_THROW(EdgeQuality<2>({-1.0, -1.0}), std::invalid_argument);
  EXPECT_THROW(EdgeQuality<3>({0.0, 1.0}), std::invalid_argument);
}

}  // namespace
}  // namespace meshmorph
