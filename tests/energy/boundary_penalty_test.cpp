// SPDX-License-Identifier: MIT
#include "meshmorph/energy/boundary_penalty.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "meshmorph/fem/structured.h"
#include "meshmorph/fem/trace.h"
#include "meshmorph/quality/metric_registry.h"

namespace meshmorph {
namespace {

// 1ᵀ M 1 = Σ_f |f| / h_f: the mass of the constant function for every order.
TEST(BoundaryMass, IntegratesOneOverTheInRadius) {
  for (int p = 1; p <= 4; ++p) {
    const int n = 3;
    const Mesh tri = structured_mesh(ElementType::Triangle, p, n);
    const BoundaryMass m = boundary_mass(tri, build_topology(tri), tri.x);
    // Right isosceles triangles with legs 1/n: in-radius (2 − √2)/(2n); perimeter 4.
    EXPECT_NEAR(m.M.sum(), 4.0 * 2.0 * n / (2.0 - std::sqrt(2.0)), 1e-9) << "order " << p;
    EXPECT_EQ(m.nodes.size(), static_cast<std::size_t>(4 * n * p));
  }
  for (int p = 1; p <= 3; ++p) {
    const int n = 2;
    const Mesh quad = structured_mesh(ElementType::Quadrilateral, p, n);
    EXPECT_NEAR(boundary_mass(quad, build_topology(quad), quad.x).M.sum(), 4.0 * 2.0 * n, 1e-9);
    const Mesh hex = structured_mesh(ElementType::Hexahedron, p, n);
    EXPECT_NEAR(boundary_mass(hex, build_topology(hex), hex.x).M.sum(), 6.0 * 2.0 * n, 1e-9);
  }
}

// uᵀMu = Σ_f ∫ u_h² / h for u = x² at the nodes of the bottom edge y = 0, 0 elsewhere (P2):
// on the bottom u_h = x² exactly; on the right edge u_h is the P2 hat of the corner (1, 0).
TEST(BoundaryMass, IntegratesQuadraticsExactly) {
  const int n = 2;
  const Mesh quad = structured_mesh(ElementType::Quadrilateral, 2, n);
  const BoundaryMass m = boundary_mass(quad, build_topology(quad), quad.x);
  Eigen::VectorXd u = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(m.nodes.size()));
  for (std::size_t i = 0; i < m.nodes.size(); ++i) {
    const auto x = quad.x.col(m.nodes[i]);
    if (std::abs(x[1]) < 1e-12) u[static_cast<Eigen::Index>(i)] = x[0] * x[0];
  }
  const double h = 1.0 / (2.0 * n), s = 1.0 / n;
  // ∫_0^1 x⁴ dx = 1/5; ∫_0^s ((1 − 2y/s)(1 − y/s))² dy = 2s/15.
  EXPECT_NEAR(u.dot(m.M * u), (1.0 / 5.0 + 2.0 * s / 15.0) / h, 1e-12);
}

template <int d>
void check_derivatives(const Mesh& mesh) {
  const Topology topo = build_topology(mesh);
  const BoundaryMass mass = boundary_mass(mesh, topo, mesh.x);
  // Constrain every boundary node but fix the first three.
  std::vector<std::int32_t> fixed(mass.nodes.begin(), mass.nodes.begin() + 3);
  std::vector<std::int32_t> constrained(mass.nodes.begin() + 3, mass.nodes.end());
  const DofMap dofs = DofMap::fixing_nodes(d, mesh.n_nodes(), fixed);
  const TargetField<d> targets = build_targets<d>(mesh, mesh.x, TargetKind::Input);
  const EnergyAssembler<d> assembler(mesh, topo, targets, dofs);
  BoundaryPenalty<d> penalty(mass, constrained);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::MatrixXd g = Eigen::MatrixXd::NullaryExpr(d, static_cast<Eigen::Index>(constrained.size()), [&] { return u(rng); });
  penalty.set_target(g);
  penalty.multipliers() = Eigen::MatrixXd::NullaryExpr(d, g.cols(), [&] { return u(rng); });
  penalty.mu = 3.5;
  Eigen::MatrixXd x = mesh.x + 0.01 * Eigen::MatrixXd::NullaryExpr(d, mesh.x.cols(), [&] { return u(rng); });

  const auto metric = make_metric<d>("distortion2");
  AssemblyOptions o;
  Assembly base, with;
  assembler.assemble(*metric, x, o, base);
  assembler.assemble(*metric, x, o, with);
  penalty.add_to(assembler, x, Want::Hessian, with);
  EXPECT_NEAR(with.value - base.value, penalty.value(x), 1e-12 * (1 + std::abs(penalty.value(x))));
  const Eigen::VectorXd grad = with.gradient - base.gradient;
  const Eigen::MatrixXd hess = Eigen::MatrixXd(with.hessian) - Eigen::MatrixXd(base.hessian);
  const double step = 1e-6;
  for (std::size_t i = 0; i < dofs.n_free(); ++i) {
    const std::int32_t dof = dofs.free_dofs()[i];
    Eigen::MatrixXd xp = x, xm = x;
    xp(dof % d, dof / d) += step;
    xm(dof % d, dof / d) -= step;
    EXPECT_NEAR(grad[static_cast<Eigen::Index>(i)], (penalty.value(xp) - penalty.value(xm)) / (2 * step), 1e-6);
    Assembly ap, am;
    assembler.assemble(*metric, xp, o, ap);
    assembler.assemble(*metric, xm, o, am);
    Assembly bp = ap, bm = am;
    penalty.add_to(assembler, xp, Want::Gradient, bp);
    penalty.add_to(assembler, xm, Want::Gradient, bm);
    const Eigen::VectorXd column = ((bp.gradient - ap.gradient) - (bm.gradient - am.gradient)) / (2 * step);
    EXPECT_LT((hess.col(static_cast<Eigen::Index>(i)) - column).norm(), 1e-6 * (1 + column.norm()));
  }
}

TEST(BoundaryPenalty, DerivativesMatchFiniteDifferences) {
  check_derivatives<2>(structured_mesh(ElementType::Triangle, 2, 2));
  check_derivatives<2>(structured_mesh(ElementType::Quadrilateral, 1, 2));
  check_derivatives<3>(structured_mesh(ElementType::Tetrahedron, 1, 1));
}

TEST(BoundaryPenalty, MultiplierUpdateAndNormsVanishAtTheTarget) {
  const Mesh mesh = structured_mesh(ElementType::Triangle, 1, 2);
  const Topology topo = build_topology(mesh);
  const BoundaryMass mass = boundary_mass(mesh, topo, mesh.x);
  BoundaryPenalty<2> penalty(mass, mass.nodes);
  Eigen::MatrixXd g(2, static_cast<Eigen::Index>(mass.nodes.size()));
  for (std::size_t a = 0; a < mass.nodes.size(); ++a) g.col(static_cast<Eigen::Index>(a)) = mesh.x.col(mass.nodes[a]);
  g.row(0).array() += 0.25;  // a translation by 0.25 in x
  penalty.set_target(g);
  penalty.mu = 2.0;
  EXPECT_NEAR(penalty.constraint_norm(mesh.x), 0.25, 1e-14);  // every node is 0.25 away
  EXPECT_NEAR(penalty.max_error(mesh.x), 0.25, 1e-14);
  penalty.update_multipliers(mesh.x);
  EXPECT_NEAR(penalty.multipliers()(0, 0), 0.5, 1e-14);  // λ − μ r = 0 − 2 · (−0.25)
  Eigen::MatrixXd x = mesh.x;
  x.row(0).array() += 0.25;
  EXPECT_NEAR(penalty.constraint_norm(x), 0.0, 1e-14);
  EXPECT_NEAR(penalty.value(x), 0.0, 1e-14);
}

}  // namespace
}  // namespace meshmorph
