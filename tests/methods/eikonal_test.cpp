// SPDX-License-Identifier: MIT
#include "meshmorph/methods/eikonal.h"

#include <cmath>
#include <cstdio>
#include <random>

#include <gtest/gtest.h>

#include "meshmorph/error.h"
#include "meshmorph/fem/trace.h"
#include "methods/deform_meshes.h"
#include "methods/detail/eikonal_residual.h"

namespace meshmorph {
namespace {

struct Errors {
  double max = 0.0, rms = 0.0;
};

// ε against the exact distance 1 − |x| to the unit sphere.
Errors distance_errors(const Mesh& mesh, const Eigen::VectorXd& eps) {
  Errors e;
  for (Eigen::Index j = 0; j < mesh.x.cols(); ++j) {
    const double err = std::abs(eps[j] - (1.0 - mesh.x.col(j).norm()));
    e.max = std::max(e.max, err);
    e.rms += err * err;
  }
  e.rms = std::sqrt(e.rms / static_cast<double>(mesh.x.cols()));
  return e;
}

TEST(EikonalResidual, JacobianMatchesCentralDifferences) {
  for (int order : {1, 2}) {
    SCOPED_TRACE(order);
    const Mesh mesh = testing::ball_mesh(ElementType::Triangle, order, 3);
    const Topology topo = build_topology(mesh);
    const detail::ScalarAssembler assembler(mesh, topo, 1, "test");
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    Eigen::VectorXd eps(mesh.x.cols()), v(mesh.x.cols());
    for (Eigen::Index i = 0; i < eps.size(); ++i) {
      eps[i] = u(rng);
      v[i] = u(rng);
    }
    Eigen::VectorXd R, Rp, Rm;
    Eigen::SparseMatrix<double> J, unused;
    detail::eikonal_residual(assembler, eps, 0.3, R, J);
    // R is quadratic in ε: central differences are exact up to rounding, whatever the step.
    const double t = 1e-3;
    detail::eikonal_residual(assembler, eps + t * v, 0.3, Rp, unused);
    detail::eikonal_residual(assembler, eps - t * v, 0.3, Rm, unused);
    const Eigen::VectorXd fd = (Rp - Rm) / (2 * t);
    EXPECT_LT((J * v - fd).norm(), 1e-10 * std::max(1.0, fd.norm()));
  }
}

// ε with Dirichlet zero on the circle (sphere) converges to 1 − |x| as the mesh is refined
// and h (one node spacing) goes to 0 with it: the convergence table is printed. The error is
// first order in h (the viscosity term), largest at the centre, where the distance has its
// cone point and the viscous solution rounds it off over a width of order h: max ≤ C h.
void expect_converges(ElementType type, int order, std::initializer_list<int> sizes) {
  double previous_rms = 0.0;
  std::printf("%-12s order %d:   n   nodes      h     max err    rms err  newton\n", std::string(name_of(type)).c_str(), order);
  for (int n : sizes) {
    const Mesh mesh = testing::ball_mesh(type, order, n);
    const Topology topo = build_topology(mesh);
    const EikonalResult r = eikonal_distance(mesh, topo, boundary_nodes(mesh, topo));
    ASSERT_TRUE(r.converged) << r.message;
    const Errors e = distance_errors(mesh, r.distance);
    std::printf("%24d %7td %8.4f %10.2e %10.2e %6d\n", n, mesh.x.cols(), r.h, e.max, e.rms, r.newton);
    if (previous_rms > 0.0) {
      EXPECT_LT(e.rms, 0.7 * previous_rms) << "n = " << n;
    }
    previous_rms = e.rms;
    EXPECT_GE(r.distance.minCoeff(), -1e-12);
    EXPECT_LT(e.max, 3.5 * r.h) << "n = " << n;  // 2.7 h in 2D, 3.1 h in 3D when written
  }
}

TEST(Eikonal, ConvergesToTheDistanceOnADiskP1) { expect_converges(ElementType::Triangle, 1, {8, 16, 32, 64}); }
TEST(Eikonal, ConvergesToTheDistanceOnADiskP2) { expect_converges(ElementType::Triangle, 2, {4, 8, 16, 32}); }
TEST(Eikonal, ConvergesToTheDistanceOnABallP1) { expect_converges(ElementType::Tetrahedron, 1, {4, 8, 16}); }

TEST(Eikonal, NaturalConditionElsewhere) {
  // Zero on the left side of the unit square only: the distance is x, exactly linear, and
  // −hΔx + |∇x|² = 1 holds with ∂x/∂n = 0 on the top and bottom; on the right side the
  // natural condition ∂ε/∂n = 0 bends ε in a layer of width ~h.
  const Mesh mesh = structured_mesh(ElementType::Triangle, 1, 16);
  const Topology topo = build_topology(mesh);
  const EikonalResult r = eikonal_distance(mesh, topo, mesh.group_nodes(*mesh.find_group("left")));
  ASSERT_TRUE(r.converged) << r.message;
  for (Eigen::Index j = 0; j < mesh.x.cols(); ++j)
    if (mesh.x(0, j) < 0.5) {
      EXPECT_NEAR(r.distance[j], mesh.x(0, j), 0.02) << j;
    }
}

// From the solution on a slightly moved mesh, Newton converges at the target h without the
// continuation, to the solution the continuation finds.
TEST(Eikonal, StartsFromAGivenSolution) {
  const Mesh mesh = testing::ball_mesh(ElementType::Triangle, 1, 16);
  const Topology topo = build_topology(mesh);
  const std::vector<std::int32_t> zero = boundary_nodes(mesh, topo);
  Mesh moved = mesh;
  moved.x *= 1.05;
  const EikonalResult before = eikonal_distance(mesh, topo, zero);
  const EikonalResult cold = eikonal_distance(moved, topo, zero);
  const EikonalResult warm = eikonal_distance(moved, topo, zero, {}, before.distance);
  ASSERT_TRUE(warm.converged) << warm.message;
  EXPECT_EQ(warm.stages, 1);
  EXPECT_LT(warm.newton, cold.newton);
  EXPECT_LT((warm.distance - cold.distance).lpNorm<Eigen::Infinity>(), 1e-8);
}

TEST(Eikonal, NoZeroNodesIsAnInputError) {
  const Mesh mesh = structured_mesh(ElementType::Triangle, 1, 2);
  EXPECT_THROW(eikonal_distance(mesh, build_topology(mesh), {}), InputError);
}

}  // namespace
}  // namespace meshmorph
