// SPDX-License-Identifier: MIT
// Every registered metric, in 2D and 3D, against finite differences at fixed-seed samples
// of T (tests/support/random_matrices.h): well shaped, anisotropic (cond 1e3),
// near-singular (τ = 1e-6|T|^d) and, for regularized metrics, inverted (τ < 0).
#include <cmath>
#include <limits>
#include <ostream>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "meshmorph/quality/metric_registry.h"
#include "support/derivative_check.h"
#include "support/random_matrices.h"

namespace meshmorph {
namespace {

struct MetricCase {
  int dim;
  std::string name;
  MetricParams params;
  std::string label;  // gtest-safe name
};

std::vector<MetricCase> all_metric_cases() {
  std::vector<MetricCase> cases;
  for (int d : {2, 3}) {
    for (const auto& name : metric_names(d)) {
      cases.push_back({d, name, {}, name + "_" + std::to_string(d) + "d"});
    }
    // Non-default parameters: the regularized edge quality (finite for τ ≤ 0), another
    // exponent, another shape/size balance.
    cases.push_back({d, "edge_quality", {{"delta", 0.1}}, "edge_quality_delta_" + std::to_string(d) + "d"});
    cases.push_back({d, "edge_quality", {{"delta", 0.02}, {"n", -2.0}}, "edge_quality_n2_" + std::to_string(d) + "d"});
    cases.push_back({d, "mu80", {{"gamma", 0.2}}, "mu80_gamma_" + std::to_string(d) + "d"});
  }
  return cases;
}

void PrintTo(const MetricCase& c, std::ostream* os) { *os << c.label; }

bool is_regularized(const MetricCase& c) {
  const auto it = c.params.find("delta");
  return c.name == "edge_quality" && it != c.params.end() && it->second > 0.0;
}

// Tolerances: the five-point rule with the step of fd_step() agrees with the analytic
// derivatives to about 1e-10 (relative, Frobenius) on the well-shaped and anisotropic
// samples. Near-singular samples reach only a few 1e-8: det T itself carries a relative
// rounding error of ε|T|^d/τ ≈ 1e-10, and the barrier amplifies it over the stencil. So
// 1e-6 for the gradient keeps a margin of 30 above the worst sample; the Hessian is
// compared with differences of the analytic gradient, which add one more such rounding
// amplification, hence 1e-5.
constexpr double kGradientTol = 1e-6;
constexpr double kHessianTol = 1e-5;

template <int d>
double singularity_distance(const MatT<d>& T) {
  // τ/|cof T| is the distance to the nearest singular matrix up to a factor ≤ √d.
  const double tau = std::abs(T.determinant());
  const MatT<d> cof = T.determinant() * T.inverse().transpose();
  return tau / cof.norm();
}

template <int d>
void check_derivatives(const MetricCase& c, bool hessian) {
  const auto metric = make_metric<d>(c.name, c.params);
  int checked = 0;
  for (const auto& s : test::matrix_samples<d>(4, is_regularized(c))) {
    SCOPED_TRACE(s.kind + ", T =\n" + ::testing::PrintToString(s.T));
    const MetricEval<d> e = metric->eval(s.T, Want::Hessian);
    ASSERT_TRUE(std::isfinite(e.mu));
    const double h = test::fd_step(is_regularized(c) ? 1.0 : singularity_distance<d>(s.T));
    const Eigen::Matrix<double, d * d, 1> x = s.T.reshaped();
    if (!hessian) {
      auto f = [&](const Eigen::Matrix<double, d * d, 1>& y) {
        return metric->eval(y.reshaped(d, d), Want::Value).mu;
      };
      const Eigen::Matrix<double, d * d, 1> g = e.dmu_dT.reshaped();
      test::expect_gradient_matches_fd(f, x, g, h, kGradientTol);
    } else {
      auto g = [&](const Eigen::Matrix<double, d * d, 1>& y) {
        return Eigen::Matrix<double, d * d, 1>(metric->eval(y.reshaped(d, d), Want::Gradient).dmu_dT.reshaped());
      };
      test::expect_hessian_matches_fd(g, x, e.d2mu_dT2, h, kHessianTol);
    }
    ++checked;
  }
  EXPECT_GE(checked, 12);
}

class MetricDerivatives : public ::testing::TestWithParam<MetricCase> {};

TEST_P(MetricDerivatives, GradientMatchesCentralDifferences) {
  const auto& c = GetParam();
  c.dim == 2 ? check_derivatives<2>(c, false) : check_derivatives<3>(c, false);
}

TEST_P(MetricDerivatives, HessianMatchesDifferencesOfGradient) {
  const auto& c = GetParam();
  c.dim == 2 ? check_derivatives<2>(c, true) : check_derivatives<3>(c, true);
}

template <int d>
void check_symmetric_and_consistent(const MetricCase& c) {
  const auto metric = make_metric<d>(c.name, c.params);
  for (const auto& s : test::matrix_samples<d>(4, is_regularized(c))) {
    SCOPED_TRACE(s.kind);
    const MetricEval<d> full = metric->eval(s.T, Want::Hessian);
    EXPECT_LE((full.d2mu_dT2 - full.d2mu_dT2.transpose()).norm(), 1e-14 * full.d2mu_dT2.norm());
    // One pass fills what is asked; the value and gradient do not depend on `want`.
    const MetricEval<d> value = metric->eval(s.T, Want::Value);
    const MetricEval<d> grad = metric->eval(s.T, Want::Gradient);
    EXPECT_EQ(value.mu, full.mu);
    EXPECT_EQ(grad.mu, full.mu);
    EXPECT_EQ((grad.dmu_dT - full.dmu_dT).norm(), 0.0);
  }
}

TEST_P(MetricDerivatives, HessianIsSymmetric) {
  const auto& c = GetParam();
  c.dim == 2 ? check_symmetric_and_consistent<2>(c) : check_symmetric_and_consistent<3>(c);
}

template <int d>
void check_inverted(const MetricCase& c) {
  const auto metric = make_metric<d>(c.name, c.params);
  MatT<d> singular = MatT<d>::Identity();
  singular(d - 1, d - 1) = 0.0;
  MatT<d> mirrored = MatT<d>::Identity();
  mirrored(0, 0) = -1.0;
  for (const MatT<d>& T : {singular, mirrored, MatT<d>(0.5 * mirrored)}) {
    const double mu = metric->eval(T, Want::Hessian).mu;
    if (is_regularized(c)) {
      EXPECT_TRUE(std::isfinite(mu)) << T;
    } else {
      EXPECT_EQ(mu, std::numeric_limits<double>::infinity()) << T;
    }
  }
}

TEST_P(MetricDerivatives, InfiniteForNonPositiveDeterminantUnlessRegularized) {
  const auto& c = GetParam();
  c.dim == 2 ? check_inverted<2>(c) : check_inverted<3>(c);
}

template <int d>
void check_left_rotation(const MetricCase& c) {
  const auto metric = make_metric<d>(c.name, c.params);
  std::mt19937 rng(7);
  for (const auto& s : test::matrix_samples<d>(3, is_regularized(c))) {
    const MatT<d> R = test::random_rotation<d>(rng);
    const double a = metric->eval(s.T, Want::Value).mu;
    const double b = metric->eval(R * s.T, Want::Value).mu;
    // det T of a near-singular T carries a relative rounding error of about ε·|T|^d/τ.
    const double tol = s.kind == "near_singular" ? 1e-8 : 1e-12;
    EXPECT_NEAR(b, a, tol * std::max(1.0, std::abs(a))) << s.kind;
  }
}

TEST_P(MetricDerivatives, InvariantUnderRotationOfTheCurrentElement) {
  const auto& c = GetParam();
  c.dim == 2 ? check_left_rotation<2>(c) : check_left_rotation<3>(c);
}

INSTANTIATE_TEST_SUITE_P(All, MetricDerivatives, ::testing::ValuesIn(all_metric_cases()),
                         [](const ::testing::TestParamInfo<MetricCase>& p) { return p.param.label; });

}  // namespace
}  // namespace meshmorph
