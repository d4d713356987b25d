// SPDX-License-Identifier: MIT
#include "meshmorph/energy/slide_constraints.h"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

namespace meshmorph {
namespace {

LevelSetFunction sphere(const Eigen::Vector3d& center, double radius) {
  LevelSet ls;
  ls.shape = SphereLevelSet{center, radius};
  return LevelSetFunction(ls, 3);
}

LevelSetFunction plane(const Eigen::Vector3d& point, const Eigen::Vector3d& normal) {
  LevelSet ls;
  ls.shape = PlaneLevelSet{point, normal};
  return LevelSetFunction(ls, 3);
}

const Eigen::Vector3d center(0.1, -0.2, 0.3);

// Nodes 0, 1 slide on a sphere, node 2 on its intersection with a plane through the centre
// (a great circle), node 3 is free.
std::vector<FitTerm> slide_terms() {
  return {{sphere(center, 0.75), {0, 1, 2}}, {plane(center, Eigen::Vector3d(1.0, 2.0, -0.5)), {2}}};
}

Eigen::MatrixXd points() {
  Eigen::MatrixXd x(3, 4);
  x << 0.9, -0.6, 0.2, 0.4, 0.1, 0.5, -0.9, 0.3, -0.3, 0.7, 0.6, 0.2;
  return x;
}

TEST(TangentBasis, IsOrthonormalAndNormalToN) {
  for (const Eigen::VectorXd& n : {Eigen::VectorXd(Eigen::Vector2d(0.6, -0.8)), Eigen::VectorXd(Eigen::Vector3d(1.0, 2.0, -2.0) / 3.0),
                                   Eigen::VectorXd(Eigen::Vector3d::UnitZ())}) {
    const Eigen::MatrixXd T = tangent_basis(n);
    ASSERT_EQ(T.cols(), n.size() - 1);
    EXPECT_LE((T.transpose() * T - Eigen::MatrixXd::Identity(T.cols(), T.cols())).norm(), 1e-15);
    EXPECT_LE((T.transpose() * n).norm(), 1e-15);
    EXPECT_LE((T * T.transpose() + n * n.transpose() - Eigen::MatrixXd::Identity(n.size(), n.size())).norm(), 1e-15);
  }
}

// The return to the surface puts a node at its closest point on a sphere, and on a great
// circle where it slides on two level sets, to rounding.
TEST(SlideConstraints, ReturnToACurvedSurfaceIsExact) {
  const std::vector<FitTerm> terms = slide_terms();
  const DofMap dofs = DofMap::all_free(3, 4);
  const SlideConstraints<3> slides(terms, dofs);
  EXPECT_EQ(slides.nodes(), (std::vector<std::int32_t>{0, 1, 2}));
  const Eigen::MatrixXd x0 = points();
  Eigen::MatrixXd x = x0;
  ASSERT_TRUE(slides.project(x, 1));
  for (int s : {0, 1}) {
    EXPECT_LE(std::abs((x.col(s) - center).norm() - 0.75), 1e-12) << s;
    const Eigen::Vector3d closest = center + 0.75 * (x0.col(s) - center).normalized();
    EXPECT_LE((x.col(s) - closest).norm(), 1e-12) << s;
  }
  for (const FitTerm& t : terms) EXPECT_LE(std::abs(t.sigma.value(x.col(2))), 1e-12);
  EXPECT_EQ(x.col(3), x0.col(3));
}

// A symmetric Hessian with a full pattern over the free DOFs, and its node blocks.
Eigen::SparseMatrix<double> random_hessian(Eigen::Index n, std::vector<double>& node_blocks) {
  Eigen::MatrixXd A = Eigen::MatrixXd::Random(n, n);
  A = (A * A.transpose()).eval();
  node_blocks.clear();
  for (Eigen::Index node = 0; node < n / 3; ++node)
    for (int l = 0; l < 3; ++l)
      for (int k = 0; k < 3; ++k) node_blocks.push_back(A(3 * node + k, 3 * node + l));
  return A.sparseView(0.0, 0.0);
}

// The frames are orthonormal with P = I − N Nᵀ; the constrained gradient is tangential, the
// constrained Hessian has c I on the normals; the matrix-free action equals the sparse one.
TEST(SlideConstraints, FramesConstrainTheHessianAndItsAction) {
  std::srand(3);
  const std::vector<FitTerm> terms = slide_terms();
  const DofMap dofs = DofMap::all_free(3, 4);
  SlideConstraints<3> sparse(terms, dofs), action(terms, dofs);
  Eigen::MatrixXd x = points();
  ASSERT_TRUE(sparse.project(x, 1));
  std::vector<double> blocks;
  Assembly a;
  a.hessian = random_hessian(12, blocks);
  const Eigen::SparseMatrix<double> H = a.hessian;
  a.gradient = Eigen::VectorXd::Random(12);
  Eigen::VectorXd g = a.gradient;
  sparse.constrain(x, HessianMode::Exact, a, 1);
  action.constrain(x, blocks, HessianMode::Exact, g);
  EXPECT_LE((g - a.gradient).norm(), 1e-15 * g.norm());
  const Eigen::MatrixXd Hc(a.hessian);
  EXPECT_LE((Hc - Hc.transpose()).norm(), 1e-14 * Hc.norm());
  for (std::int32_t node : {0, 1, 2}) {
    const auto* f = sparse.frame_of_row(3 * node);
    ASSERT_NE(f, nullptr);
    const auto m = f->N.cols();
    EXPECT_EQ(m, node == 2 ? 2 : 1);
    EXPECT_LE((f->N.transpose() * f->N - Eigen::MatrixXd::Identity(m, m)).norm(), 1e-14);
    EXPECT_LE((f->P - (Eigen::Matrix3d::Identity() - f->N * f->N.transpose())).norm(), 1e-15);
    EXPECT_LE((f->N.transpose() * a.gradient.segment<3>(3 * node)).norm(), 1e-14 * g.norm());
    const Eigen::Matrix3d B = Hc.block<3, 3>(3 * node, 3 * node);
    const Eigen::MatrixXd normal = f->N.transpose() * B * f->N;
    EXPECT_LE((normal - normal(0, 0) * Eigen::MatrixXd::Identity(m, m)).norm(), 1e-13 * B.norm());
    EXPECT_GT(normal(0, 0), 0.0);
    // The rows of the node against every other node are tangential.
    EXPECT_LE((f->N.transpose() * Hc.middleRows<3>(3 * node)).rightCols(12 - 3 * node - 3).norm(), 1e-14 * Hc.norm());
  }
  EXPECT_EQ(sparse.frame_of_row(1), nullptr);
  EXPECT_EQ(sparse.frame_of_row(9), nullptr);
  const Eigen::VectorXd v = Eigen::VectorXd::Random(12);
  Eigen::VectorXd pv, y;
  action.tangential(v, pv);
  y = H * pv;
  action.finish_action(v, y);
  EXPECT_LE((y - Hc * v).norm(), 1e-13 * (Hc * v).norm());
}

}  // namespace
}  // namespace meshmorph
