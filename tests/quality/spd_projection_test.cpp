// SPDX-License-Identifier: MIT
#include "meshmorph/quality/spd_projection.h"

#include <random>

#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include "meshmorph/quality/metric_registry.h"
#include "support/random_matrices.h"

namespace meshmorph {
namespace {

template <int d>
double min_eigenvalue(const HessT<d>& H) {
  return Eigen::SelfAdjointEigenSolver<HessT<d>>(H).eigenvalues().minCoeff();
}

template <int d>
void check_metric_hessians_become_psd() {
  int clamped = 0;
  for (const auto& name : metric_names(d)) {
    const auto metric = make_metric<d>(name);
    for (const auto& s : test::matrix_samples<d>(3, false)) {
      HessT<d> H = metric->eval(s.T, Want::Hessian).d2mu_dT2;
      const HessT<d> before = H;
      const bool changed = project_spd<d>(H);
      clamped += changed;
      EXPECT_GE(min_eigenvalue<d>(H), -1e-12 * H.norm()) << name << " " << s.kind;
      EXPECT_EQ(changed, min_eigenvalue<d>(before) < 0.0) << name << " " << s.kind;
      // The projection is the nearest PSD matrix: it changes only the negative part.
      const HessT<d> delta = H - before;
      EXPECT_GE(min_eigenvalue<d>(delta), -1e-10 * (1 + H.norm())) << name << " " << s.kind;
    }
  }
  EXPECT_GT(clamped, 0);  // the shape metrics are not convex in T: some Hessians are indefinite
}

TEST(ProjectSpd, MetricHessiansBecomePositiveSemidefinite) {
  check_metric_hessians_become_psd<2>();
  check_metric_hessians_become_psd<3>();
}

TEST(ProjectSpd, LeavesPositiveDefiniteMatricesUnchanged) {
  std::mt19937 rng(11);
  std::normal_distribution<double> n(0.0, 1.0);
  for (int k = 0; k < 10; ++k) {
    HessT<3> B;
    for (int i = 0; i < B.size(); ++i) B(i) = n(rng);
    HessT<3> H = B * B.transpose() + 1e-3 * HessT<3>::Identity();
    const HessT<3> before = H;
    EXPECT_FALSE(project_spd<3>(H, 1e-6));
    EXPECT_EQ((H - before).norm(), 0.0);  // bit for bit
  }
}

TEST(ProjectSpd, RaisesEigenvaluesToTheFloor) {
  HessT<2> H = Eigen::Vector4d(-3.0, 0.0, 1e-9, 5.0).asDiagonal();
  EXPECT_TRUE(project_spd<2>(H, 1e-6));
  const Eigen::Vector4d expected(1e-6, 1e-6, 1e-6, 5.0);
  EXPECT_LE((H.diagonal() - expected).norm(), 1e-14);
  EXPECT_LE((H - HessT<2>(H.diagonal().asDiagonal())).norm(), 1e-14);
}

}  // namespace
}  // namespace meshmorph
