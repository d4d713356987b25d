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
      const bool changed = project_spd(H);
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
    EXPECT_FALSE(project_spd(H, 1e-6));
    EXPECT_EQ((H - before).norm(), 0.0);  // bit for bit
  }
}

TEST(ProjectSpd, RaisesEigenvaluesToTheFloor) {
  HessT<2> H = Eigen::Vector4d(-3.0, 0.0, 1e-9, 5.0).asDiagonal();
  EXPECT_TRUE(project_spd(H, 1e-6));
  const Eigen::Vector4d expected(1e-6, 1e-6, 1e-6, 5.0);
  EXPECT_LE((H.diagonal() - expected).norm(), 1e-14);
  EXPECT_LE((H - HessT<2>(H.diagonal().asDiagonal())).norm(), 1e-14);
}

// A d×d block (fixed size or dynamic) takes the projection of the metric Hessians: the same
// result for the same matrix whatever its type, to rounding.
TEST(ProjectSpd, AnySizeTakesTheSameProjection) {
  Eigen::Matrix3d B;
  B << 2.0, 1.0, 0.0, 1.0, -1.0, 0.5, 0.0, 0.5, 1e-3;
  Eigen::MatrixXd D = B;
  EXPECT_TRUE(project_spd(B));
  EXPECT_TRUE(project_spd(D));
  EXPECT_LE((Eigen::MatrixXd(B) - D).norm(), 1e-14);
  EXPECT_GE(Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(B).eigenvalues().minCoeff(), -1e-15);
  Eigen::Matrix2d P;
  P << 2.0, 1.0, 1.0, 3.0;
  const Eigen::Matrix2d before = P;
  EXPECT_FALSE(project_spd(P));
  EXPECT_EQ((P - before).norm(), 0.0);
  HessT<3> H = HessT<3>::Identity();
  H(4, 4) = -2.0;
  Eigen::MatrixXd G = H;
  project_spd(H);
  project_spd(G);
  EXPECT_LE((Eigen::MatrixXd(H) - G).norm(), 1e-14);
}

}  // namespace
}  // namespace meshmorph
