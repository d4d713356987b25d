// SPDX-License-Identifier: MIT
#include "meshmorph/energy/level_set_penalty.h"

#include <vector>

#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include "support/derivative_check.h"

namespace meshmorph {
namespace {

LevelSetFunction sphere(const Eigen::VectorXd& center, double radius) {
  LevelSet ls;
  ls.shape = SphereLevelSet{center, radius};
  return LevelSetFunction(ls, static_cast<int>(center.size()));
}

LevelSetFunction plane(const Eigen::VectorXd& point, const Eigen::VectorXd& normal) {
  LevelSet ls;
  ls.shape = PlaneLevelSet{point, normal};
  return LevelSetFunction(ls, static_cast<int>(point.size()));
}

// The pattern an assembler gives the penalty: every node's free DOFs in one dense block.
Eigen::SparseMatrix<double> block_pattern(const DofMap& dofs) {
  std::vector<Eigen::Triplet<double>> t;
  for (std::size_t node = 0; node < dofs.n_nodes(); ++node)
    for (std::int32_t i = dofs.first(node); i < dofs.first(node + 1); ++i)
      for (std::int32_t j = dofs.first(node); j < dofs.first(node + 1); ++j) t.emplace_back(i, j, 0.0);
  const auto n = static_cast<Eigen::Index>(dofs.n_free());
  Eigen::SparseMatrix<double> H(n, n);
  H.setFromTriplets(t.begin(), t.end());
  return H;
}

// Four nodes off a sphere and a plane (σ ≠ 0, curvature in play), node 2 on both terms and
// with one fixed DOF: the value, gradient and Hessian against differences of F_σ.
template <int d>
void check_derivatives() {
  Eigen::MatrixXd x3(3, 4);
  x3 << 0.8, -0.4, 0.3, 0.5, 0.2, 0.6, -0.7, 0.5, -0.3, 0.5, 0.4, 0.9;
  const Eigen::MatrixXd x = x3.topRows(d);
  std::vector<std::uint8_t> fixed(static_cast<std::size_t>(d) * 4, 0);
  fixed[static_cast<std::size_t>(d) * 2 + 1] = 1;
  const DofMap dofs = DofMap::from_mask(d, fixed);
  const Eigen::VectorXd c = Eigen::VectorXd::Constant(d, 0.1), n = Eigen::VectorXd::LinSpaced(d, 1.0, 2.0);
  const std::vector<FitTerm> terms{{sphere(c, 0.5), {0, 1, 2}}, {plane(c, n), {2, 3}}};
  LevelSetPenalty<d> penalty(terms, dofs);
  penalty.weight = 3.0;
  const auto at = [&](const Eigen::VectorXd& y) {
    Eigen::MatrixXd z = x;
    dofs.add_step(y, 1.0, z);
    return z;
  };
  const auto n_free = static_cast<Eigen::Index>(dofs.n_free());
  const auto gradient = [&](const Eigen::VectorXd& y) {
    Assembly a;
    a.gradient = Eigen::VectorXd::Zero(n_free);
    penalty.add_to(at(y), Want::Gradient, HessianMode::Exact, a);
    return Eigen::VectorXd(a.gradient);
  };
  const Eigen::VectorXd y0 = Eigen::VectorXd::Zero(n_free);
  Assembly a;
  a.gradient = Eigen::VectorXd::Zero(n_free);
  a.hessian = block_pattern(dofs);
  penalty.add_to(x, Want::Hessian, HessianMode::Exact, a);
  double expected = 0.0;
  for (const FitTerm& t : terms)
    for (std::int32_t s : t.nodes) expected += 3.0 * std::pow(t.sigma.value(x.col(s)), 2);
  EXPECT_NEAR(a.value, expected, 1e-14 * expected);
  EXPECT_NEAR(penalty.value(x), expected, 1e-14 * expected);
  test::expect_gradient_matches_fd([&](const Eigen::VectorXd& y) { return penalty.value(at(y)); }, y0, a.gradient, 1e-3, 1e-9);
  test::expect_hessian_matches_fd(gradient, y0, Eigen::MatrixXd(a.hessian), 1e-3, 1e-9);

  // Projected: the same blocks raised onto the PSD cone, the gradient unchanged.
  Assembly p;
  p.gradient = Eigen::VectorXd::Zero(n_free);
  p.hessian = block_pattern(dofs);
  penalty.add_to(x, Want::Hessian, HessianMode::Projected, p);
  EXPECT_EQ((p.gradient - a.gradient).norm(), 0.0);
  const Eigen::MatrixXd Hp(p.hessian);
  EXPECT_GE(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(Hp).eigenvalues().minCoeff(), -1e-12 * Hp.norm());
}

TEST(LevelSetPenalty, DerivativesMatchDifferences) {
  check_derivatives<2>();
  check_derivatives<3>();
}

TEST(LevelSetPenalty, ErrorStiffnessAndFittedNodes) {
  const DofMap dofs = DofMap::all_free(2, 3);
  Eigen::MatrixXd x(2, 3);
  x << 0.0, 0.5, 0.0, 0.0, 0.0, -0.75;
  const std::vector<FitTerm> terms{{sphere(Eigen::Vector2d::Zero(), 0.5), {1, 2}}};
  const LevelSetPenalty<2> penalty(terms, dofs);
  EXPECT_DOUBLE_EQ(penalty.max_error(x), 0.25);
  const Eigen::VectorXd diagonal = Eigen::VectorXd::LinSpaced(6, 1.0, 6.0);
  EXPECT_DOUBLE_EQ(penalty.mean_at_nodes(diagonal), (3.0 + 4.0 + 5.0 + 6.0) / 4.0);
  EXPECT_DOUBLE_EQ(penalty.mean_at_nodes(-diagonal), 1.0);
  EXPECT_EQ(penalty.fitted(3), (std::vector<std::uint8_t>{0, 1, 1}));
}

}  // namespace
}  // namespace meshmorph
