// SPDX-License-Identifier: MIT
#include "meshmorph/energy/validity_guard.h"

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "energy/energy_fixtures.h"
#include "meshmorph/energy/assembler.h"
#include "meshmorph/fem/structured.h"
#include "meshmorph/fem/validity.h"
#include "meshmorph/mesh/topology.h"

namespace meshmorph {
namespace {

using test::test_metric;

// The guard's share of an assembly (Exact Hessian): the assembly with it minus the one without.
template <int d>
struct GuardShare {
  double value;
  Eigen::VectorXd gradient;
  Eigen::MatrixXd hessian;
};

template <int d>
GuardShare<d> share(const EnergyAssembler<d>& assembler, const ValidityGuard<d>& guard, const Metric<d>& metric,
                    const Eigen::MatrixXd& x, const std::vector<double>& weights) {
  AssemblyOptions o;
  o.hessian = HessianMode::Exact;
  o.weights = weights;
  Assembly base, with;
  assembler.assemble(metric, x, o, base);
  assembler.assemble(metric, x, o, with);
  guard.add_to(metric, x, weights, Want::Hessian, HessianMode::Exact, with);
  return {with.value - base.value, with.gradient - base.gradient,
          Eigen::MatrixXd(with.hessian) - Eigen::MatrixXd(base.hessian)};
}

// Gradient and Hessian of the guard (added into an assembly over free DOFs, cell weights
// ω_e) against central differences of its value and gradient, on a perturbed curved mesh
// with some nodes fixed and every third cell guarded.
template <int d>
void check_derivatives(const Mesh& mesh) {
  const Topology topo = build_topology(mesh);
  std::vector<std::int32_t> fixed = {0, 1, 2};
  const DofMap dofs = DofMap::fixing_nodes(d, mesh.n_nodes(), fixed);
  const TargetField<d> targets = build_targets<d>(mesh, mesh.x, TargetKind::Input);
  const EnergyAssembler<d> assembler(mesh, topo, targets, dofs);
  ValidityGuard<d> guard(mesh, dofs);
  std::vector<std::size_t> cells;
  for (std::size_t c = 0; c < mesh.n_cells(); c += 3) cells.push_back(c);
  ASSERT_EQ(guard.add(cells), cells.size());
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> weights(mesh.n_cells());
  for (double& w : weights) w = 1.0 + 0.5 * (u(rng) + 1.0);
  const Eigen::MatrixXd x =
      mesh.x + 0.02 * Eigen::MatrixXd::NullaryExpr(d, static_cast<Eigen::Index>(mesh.n_nodes()), [&] { return u(rng); });
  const auto metric = test_metric<d>();
  const GuardShare<d> at = share(assembler, guard, *metric, x, weights);
  ASSERT_TRUE(std::isfinite(at.value));
  EXPECT_NEAR(at.value, guard.value(*metric, x, weights), 1e-12 * std::abs(at.value));
  const double step = 1e-6;
  double gradient_error = 0.0, hessian_error = 0.0;
  for (std::size_t i = 0; i < dofs.n_free(); ++i) {
    const std::int32_t dof = dofs.free_dofs()[i];
    Eigen::MatrixXd xp = x, xm = x;
    xp(dof % d, dof / d) += step;
    xm(dof % d, dof / d) -= step;
    const double fd = (guard.value(*metric, xp, weights) - guard.value(*metric, xm, weights)) / (2 * step);
    gradient_error = std::max(gradient_error, std::abs(at.gradient[static_cast<Eigen::Index>(i)] - fd) / (1 + std::abs(fd)));
    const Eigen::VectorXd column =
        (share(assembler, guard, *metric, xp, weights).gradient - share(assembler, guard, *metric, xm, weights).gradient) /
        (2 * step);
    hessian_error = std::max(hessian_error, (at.hessian.col(static_cast<Eigen::Index>(i)) - column).norm() / (1 + column.norm()));
  }
  EXPECT_LT(gradient_error, 1e-6);
  EXPECT_LT(hessian_error, 1e-6);
  EXPECT_GT(at.gradient.norm(), 1e-3);  // the perturbation is felt: the comparison means something
}

TEST(ValidityGuard, DerivativesMatchFiniteDifferences) {
  check_derivatives<2>(structured_mesh(ElementType::Triangle, 2, 2));
  check_derivatives<2>(structured_mesh(ElementType::Quadrilateral, 3, 2));
  check_derivatives<3>(structured_mesh(ElementType::Tetrahedron, 2, 1));
  check_derivatives<3>(structured_mesh(ElementType::Hexahedron, 2, 1));
}

// At a similarity of the input, μ = η² = 1 at every sample: the guard is the guarded cells'
// input volume (their sample weights sum to it on straight-sided cells) and its gradient is
// zero, so it leaves an exact affine motion exact.
TEST(ValidityGuard, IsTheGuardedVolumeAndStationaryAtASimilarity) {
  const Mesh mesh = structured_mesh(ElementType::Tetrahedron, 2, 2);
  const Topology topo = build_topology(mesh);
  const DofMap dofs = DofMap::fixing_nodes(3, mesh.n_nodes(), {});
  const TargetField<3> targets = build_targets<3>(mesh, mesh.x, TargetKind::Input);
  const EnergyAssembler<3> assembler(mesh, topo, targets, dofs);
  ValidityGuard<3> guard(mesh, dofs);
  const std::vector<std::size_t> cells = {0, 5, 17, 40};
  EXPECT_EQ(guard.add(cells), 4u);
  EXPECT_EQ(guard.add(std::vector<std::size_t>{5, 17, 41}), 1u);  // only 41 is new
  EXPECT_TRUE(guard.contains(41));
  EXPECT_FALSE(guard.contains(1));
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, -2, 0.5).normalized()).toRotationMatrix();
  const Eigen::MatrixXd x = ((1.7 * R * mesh.x).colwise() + Eigen::Vector3d(0.3, -4.0, 2.0)).eval();
  const auto metric = test_metric<3>();
  const std::vector<double> weights;
  const GuardShare<3> at = share(assembler, guard, *metric, x, weights);
  const double cell_volume = 1.0 / 48.0;  // structured_mesh: the unit cube, 2³ cubes of 6 tets
  EXPECT_NEAR(at.value, 5 * cell_volume, 1e-13);
  EXPECT_LT(at.gradient.cwiseAbs().maxCoeff(), 1e-12);
}

// A P2 triangle whose edge node slides towards a vertex: from a quarter of the edge on, det A
// is negative at that vertex while every quadrature point stays positive. The metric's energy
// is finite there; the guard's is +∞ once the cell is guarded, and 0 while no cell is.
TEST(ValidityGuard, IsInfiniteWhereAGuardedCellFoldsAtANodeOnly) {
  Eigen::MatrixXd X(2, 6);
  X << 0, 1, 0, 0.5, 0.5, 0, 0, 0, 1, 0, 0.5, 0.5;  // Gmsh order: vertices, then edges 01, 12, 20
  X(0, 3) = 0.2;  // the node of edge 01 at a fifth of the edge
  const Mesh mesh = test::one_cell_mesh(ElementType::Triangle, 2, X);
  Mesh input = mesh;
  input.x.col(3) << 0.5, 0.0;
  const Topology topo = build_topology(input);
  const DofMap dofs = DofMap::fixing_nodes(2, input.n_nodes(), {});
  const TargetField<2> targets = build_targets<2>(input, input.x, TargetKind::Input);
  const EnergyAssembler<2> assembler(input, topo, targets, dofs);
  const auto metric = test_metric<2>();
  ASSERT_LT(min_jacobian_det(ElementType::Triangle, 2, X), 0.0);
  EXPECT_TRUE(std::isfinite(assembler.value(*metric, X)));
  ValidityGuard<2> guard(input, dofs);
  EXPECT_EQ(guard.value(*metric, X, {}), 0.0);
  guard.add(std::vector<std::size_t>{0});
  EXPECT_EQ(guard.value(*metric, X, {}), std::numeric_limits<double>::infinity());
  EXPECT_TRUE(std::isfinite(guard.value(*metric, input.x, {})));
}

}  // namespace
}  // namespace meshmorph
