// SPDX-License-Identifier: MIT
#include "meshmorph/energy/element_energy.h"

#include <cmath>
#include <limits>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "energy/energy_fixtures.h"
#include "meshmorph/error.h"
#include "support/derivative_check.h"
#include "support/element_cases.h"

namespace meshmorph {
namespace {

using test::ElementCase;

// The energy of an element and its derivatives at X (d × n), against targets built from X0.
template <int d>
struct ElementProblem {
  Mesh mesh;
  TargetField<d> targets;
  std::unique_ptr<Metric<d>> metric;

  ElementProblem(const ElementCase& c, const Eigen::MatrixXd& X0, TargetKind kind, const std::string& name)
      : mesh(test::one_cell_mesh(c.type, c.order, X0)),
        targets(build_targets<d>(mesh, mesh.x, kind)),
        metric(test::test_metric<d>(name)) {}

  ElementEnergy at(const Eigen::VectorXd& vecX, Want want, HessianMode mode = HessianMode::Exact) const {
    const Eigen::Matrix<double, d, Eigen::Dynamic> X = Eigen::Map<const Eigen::MatrixXd>(vecX.data(), d, vecX.size() / d);
    const BlockTargets<d>& bt = targets.blocks[0];
    return element_energy<d>(*metric, *bt.table, {bt.cell(0), static_cast<std::size_t>(bt.n_points())}, X, want, mode);
  }
};

class ElementEnergyDerivatives : public ::testing::TestWithParam<ElementCase> {
 protected:
  // Gradient and exact Hessian against five-point differences, for both targets. Tolerance
  // 1e-6 as the issue asks; fd_step(0.1) keeps the step well inside the validity region of
  // elements whose nodes move by ≤ 0.08/order.
  template <int d>
  void check(const std::string& metric) {
    const ElementCase c = GetParam();
    for (TargetKind kind : {TargetKind::Input, TargetKind::Ideal}) {
      SCOPED_TRACE(kind == TargetKind::Input ? "input target" : "ideal target");
      const Eigen::MatrixXd X0 = test::random_element(c.type, c.order, 7u + static_cast<unsigned>(c.order));
      const Eigen::MatrixXd X1 = test::random_element(c.type, c.order, 99u + static_cast<unsigned>(c.order));
      const ElementProblem<d> p(c, X0, kind, metric);
      const Eigen::VectorXd x = Eigen::Map<const Eigen::VectorXd>(X1.data(), X1.size());
      const ElementEnergy e = p.at(x, Want::Hessian);
      ASSERT_TRUE(std::isfinite(e.value));
      EXPECT_GT(e.value, 0.0);
      const double h = test::fd_step(0.1);
      test::expect_gradient_matches_fd([&](const Eigen::VectorXd& y) { return p.at(y, Want::Value).value; }, x, e.gradient,
                                       h, 1e-6);
      test::expect_hessian_matches_fd([&](const Eigen::VectorXd& y) { return p.at(y, Want::Gradient).gradient; }, x,
                                      e.hessian, h, 1e-6);
      EXPECT_EQ((e.hessian - e.hessian.transpose()).norm(), 0.0);
    }
  }
};

TEST_P(ElementEnergyDerivatives, MatchFiniteDifferences) {
  if (topological_dim(GetParam().type) == 2) {
    check<2>("distortion2");
    check<2>("mu2");
  } else {
    check<3>("distortion2");
    check<3>("mu303");
  }
}

class ElementEnergyProperties : public ::testing::TestWithParam<ElementCase> {
 protected:
  template <int d>
  void projected_is_psd() {
    const ElementCase c = GetParam();
    const Eigen::MatrixXd X0 = test::random_element(c.type, c.order, 3);
    // A strongly distorted (but valid) state, where d²μ/dT² is indefinite somewhere.
    const Eigen::MatrixXd X1 = test::random_element(c.type, c.order, 5, 0.2);
    const ElementProblem<d> p(c, X0, TargetKind::Input, "distortion2");
    const Eigen::VectorXd x = Eigen::Map<const Eigen::VectorXd>(X1.data(), X1.size());
    const ElementEnergy e = p.at(x, Want::Hessian, HessianMode::Projected);
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(e.hessian);
    const double scale = e.hessian.cwiseAbs().maxCoeff();
    EXPECT_GE(eig.eigenvalues().minCoeff(), -1e-12 * scale);
    // The projection changes the Hessian only: value and gradient are the exact ones.
    const ElementEnergy exact = p.at(x, Want::Hessian, HessianMode::Exact);
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> exact_eig(exact.hessian);
    EXPECT_LT(exact_eig.eigenvalues().minCoeff(), -1e-6 * scale) << "the case does not exercise the projection";
    EXPECT_EQ(exact.value, e.value);
    EXPECT_EQ((exact.gradient - e.gradient).norm(), 0.0);
  }

  template <int d>
  void similarity_is_optimal() {
    // η = 1 at every point of any similarity of the input (T = sR): E = volume·1, ∇E = 0.
    const ElementCase c = GetParam();
    const Eigen::MatrixXd X0 = test::random_element(c.type, c.order, 11);
    const ElementProblem<d> p(c, X0, TargetKind::Input, "distortion");
    Eigen::MatrixXd R = Eigen::MatrixXd::Identity(d, d);
    const double t = 0.7;
    R.topLeftCorner(2, 2) << std::cos(t), -std::sin(t), std::sin(t), std::cos(t);
    if (d == 3) R = R * Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix().topLeftCorner(d, d);
    Eigen::MatrixXd X1 = 1.7 * R * X0;
    X1.colwise() += Eigen::VectorXd::Constant(d, 0.4);
    const Eigen::VectorXd x = Eigen::Map<const Eigen::VectorXd>(X1.data(), X1.size());
    const ElementEnergy e = p.at(x, Want::Gradient);
    double volume = 0.0;
    for (const auto& q : p.targets.blocks[0].points) volume += q.weight;
    EXPECT_NEAR(e.value, volume, 1e-12 * volume);
    EXPECT_LE(e.gradient.norm(), 1e-11);
  }

  template <int d>
  void inverted_is_infinite() {
    const ElementCase c = GetParam();
    const Eigen::MatrixXd X0 = test::random_element(c.type, c.order, 13);
    const ElementProblem<d> p(c, X0, TargetKind::Input, "distortion2");
    Eigen::MatrixXd X1 = X0;
    X1.row(0) *= -1.0;  // a reflection: det A < 0 everywhere
    const Eigen::VectorXd x = Eigen::Map<const Eigen::VectorXd>(X1.data(), X1.size());
    EXPECT_EQ(p.at(x, Want::Value).value, std::numeric_limits<double>::infinity());
    EXPECT_EQ(p.at(x, Want::Hessian).value, std::numeric_limits<double>::infinity());
  }

  template <int d>
  void run_all() {
    projected_is_psd<d>();
    similarity_is_optimal<d>();
    inverted_is_infinite<d>();
  }
};

TEST_P(ElementEnergyProperties, PsdProjectionSimilarityAndInversion) {
  if (topological_dim(GetParam().type) == 2)
    run_all<2>();
  else
    run_all<3>();
}

INSTANTIATE_TEST_SUITE_P(All, ElementEnergyDerivatives, ::testing::ValuesIn(test::all_cell_cases()), test::CaseName());
INSTANTIATE_TEST_SUITE_P(PrismPyramid, ElementEnergyDerivatives, ::testing::ValuesIn(test::prism_pyramid_cases()), test::CaseName());
INSTANTIATE_TEST_SUITE_P(All, ElementEnergyProperties, ::testing::ValuesIn(test::all_cell_cases()), test::CaseName());
INSTANTIATE_TEST_SUITE_P(PrismPyramid, ElementEnergyProperties, ::testing::ValuesIn(test::prism_pyramid_cases()), test::CaseName());

TEST(IdealJacobian, HasTheRequestedVolumeAndShape) {
  const MatT<2> Wt = ideal_jacobian<2>(ElementType::Triangle, 3.0);
  EXPECT_NEAR(Wt.determinant() / 2.0, 3.0, 1e-12);
  // Edges of the image of the unit triangle are equal (regular simplex).
  const Eigen::Vector2d e1 = Wt.col(0), e2 = Wt.col(1);
  EXPECT_NEAR(e1.norm(), e2.norm(), 1e-12);
  EXPECT_NEAR(e1.norm(), (e2 - e1).norm(), 1e-12);
  const MatT<3> Wtet = ideal_jacobian<3>(ElementType::Tetrahedron, 2.0);
  EXPECT_NEAR(Wtet.determinant() / 6.0, 2.0, 1e-12);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < i; ++j) EXPECT_NEAR((Wtet.col(i) - Wtet.col(j)).norm(), Wtet.col(0).norm(), 1e-12);
  const MatT<3> Whex = ideal_jacobian<3>(ElementType::Hexahedron, 8.0);
  EXPECT_TRUE(Whex.isApprox(MatT<3>::Identity(), 1e-14));  // [−1,1]³ has volume 8
}

// MFEM's -tid 1: every cell's weights sum to the volume of the unit-edge regular simplex or
// of the unit square/cube, whatever the cell's size, where the ideal target's sum to the
// cell's own volume; both share the ideal shape.
TEST(BuildTargets, IdealUnitWeighsEveryCellAsTheUnitCell) {
  for (const ElementCase c : test::all_cell_cases()) {
    SCOPED_TRACE(test::case_name(c));
    const int dim = topological_dim(c.type);
    const Eigen::MatrixXd X = 3.0 * test::random_element(c.type, c.order, 5u);  // a cell of about 3^dim the unit's volume
    const Mesh mesh = test::one_cell_mesh(c.type, c.order, X);
    const auto sums = [&](TargetKind kind) {
      double sum = 0.0;
      Eigen::MatrixXd W_inv;
      if (dim == 2) {
        const TargetField<2> t = build_targets<2>(mesh, mesh.x, kind);
        for (const auto& q : t.blocks[0].points) sum += q.weight;
        W_inv = t.blocks[0].points[0].W_inv;
      } else {
        const TargetField<3> t = build_targets<3>(mesh, mesh.x, kind);
        for (const auto& q : t.blocks[0].points) sum += q.weight;
        W_inv = t.blocks[0].points[0].W_inv;
      }
      return std::make_pair(sum, W_inv);
    };
    const auto [unit, W_unit] = sums(TargetKind::IdealUnit);
    const auto [own, W_own] = sums(TargetKind::Ideal);
    const double expected = is_simplex(c.type) ? (dim == 2 ? std::sqrt(3.0) / 4.0 : 1.0 / (6.0 * std::sqrt(2.0))) : 1.0;
    EXPECT_NEAR(unit, expected, 1e-12);
    EXPECT_GT(own, 2.0 * expected);
    EXPECT_NEAR((W_unit - std::pow(own / unit, 1.0 / dim) * W_own).norm(), 0.0, 1e-12 * W_unit.norm());  // same shape
  }
  EXPECT_EQ(target_kind(target_name(TargetKind::IdealUnit)), TargetKind::IdealUnit);
  EXPECT_THROW(target_kind("unit"), std::invalid_argument);
}

TEST(BuildTargets, InvertedInputElementIsAnInputError) {
  Eigen::MatrixXd X(2, 3);
  X << 0, 0, 1, 0, 1, 0;  // clockwise triangle
  const Mesh mesh = test::one_cell_mesh(ElementType::Triangle, 1, X);
  EXPECT_THROW(build_targets<2>(mesh, mesh.x, TargetKind::Input), InputError);
  EXPECT_NO_THROW(build_targets<2>(mesh, mesh.x, TargetKind::Ideal));
}

}  // namespace
}  // namespace meshmorph
