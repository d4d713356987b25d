// SPDX-License-Identifier: MIT
#include "meshmorph/methods/baselines.h"

#include <cmath>
#include <functional>
#include <numbers>
#include <random>
#include <tuple>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "meshmorph/error.h"
#include "meshmorph/fem/structured.h"
#include "meshmorph/fem/trace.h"
#include "meshmorph/fem/validity.h"
#include "methods/detail/stiffness.h"
#include "support/element_cases.h"

namespace meshmorph {
namespace {

using Map = std::function<Eigen::VectorXd(const Eigen::VectorXd&)>;

// A structured mesh with its strictly interior nodes moved at random by up to `amount` (10%)
// of the node spacing: cells of different sizes (so stiffening acts) and, for order ≥ 2,
// curved cells.
Mesh perturbed_mesh(ElementType type, int order, int n, unsigned seed = 7, double amount = 0.1) {
  Mesh mesh = structured_mesh(type, order, n);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double h = amount / (n * order);
  for (Eigen::Index j = 0; j < mesh.x.cols(); ++j) {
    const bool inside = (mesh.x.col(j).array() > 1e-12).all() && (mesh.x.col(j).array() < 1.0 - 1e-12).all();
    if (inside)
      for (Eigen::Index k = 0; k < mesh.x.rows(); ++k) mesh.x(k, j) += h * u(rng);
  }
  return mesh;
}

// Every node Free with target = input position, normal 0.
BoundaryTargets free_targets(const Mesh& mesh) {
  BoundaryTargets bc;
  bc.role.assign(mesh.n_nodes(), NodeRole::Free);
  bc.target = mesh.x;
  bc.normal = Eigen::MatrixXd::Zero(mesh.dim, static_cast<Eigen::Index>(mesh.n_nodes()));
  return bc;
}

void prescribe(BoundaryTargets& bc, const Mesh& mesh, std::int32_t j, const Map& map) {
  bc.role[static_cast<std::size_t>(j)] = NodeRole::Prescribed;
  bc.target.col(j) = map(mesh.x.col(j));
}

// Every boundary node (all orders) Prescribed to map(x).
BoundaryTargets boundary_moved_by(const Mesh& mesh, const Topology& topo, const Map& map) {
  BoundaryTargets bc = free_targets(mesh);
  for (std::int32_t j : boundary_nodes(mesh, topo)) prescribe(bc, mesh, j, map);
  return bc;
}

double max_error(const Eigen::MatrixXd& x, const Mesh& mesh, const Map& map) {
  double e = 0.0;
  for (Eigen::Index j = 0; j < x.cols(); ++j) e = std::max(e, (x.col(j) - map(mesh.x.col(j))).norm());
  return e;
}

Eigen::MatrixXd rotation(int d, double degrees) {
  const double a = degrees * std::numbers::pi / 180.0;
  if (d == 2) return Eigen::Rotation2Dd(a).toRotationMatrix();
  return Eigen::AngleAxisd(a, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
}

// Translation, rotation about (0.5, …) and a general affine map with shear and stretch.
std::vector<std::pair<std::string, Map>> affine_maps(int d) {
  const Eigen::VectorXd c = Eigen::VectorXd::Constant(d, 0.5);
  const Eigen::VectorXd t = Eigen::VectorXd::LinSpaced(d, 0.3, -0.2);
  const Eigen::MatrixXd R = rotation(d, 40.0);
  Eigen::MatrixXd M = Eigen::MatrixXd::Identity(d, d);
  M(0, 1) = 0.4;
  M(1, 0) = -0.15;
  M(d - 1, d - 1) = 1.3;
  return {{"translation", [t](const Eigen::VectorXd& x) -> Eigen::VectorXd { return x + t; }},
          {"rotation", [R, c](const Eigen::VectorXd& x) -> Eigen::VectorXd { return c + R * (x - c); }},
          {"affine", [M, t](const Eigen::VectorXd& x) -> Eigen::VectorXd { return M * x + t; }}};
}

BaselineOptions cholesky(double stiffening = 0.0) {
  BaselineOptions o;
  o.solver = LinearSolverKind::Cholesky;
  o.stiffening = stiffening;
  return o;
}

class BaselinesByElement : public ::testing::TestWithParam<test::ElementCase> {
 protected:
  Mesh mesh() const {
    const auto c = GetParam();
    // 5% on quartic prisms: 10% folds two of them at a quadrature point (and six quartic
    // tetrahedra between theirs).
    const double amount = c.type == ElementType::Prism && c.order == 4 ? 0.05 : 0.1;
    return perturbed_mesh(c.type, c.order, topological_dim(c.type) == 2 ? 3 : 2, 7, amount);
  }
};

TEST_P(BaselinesByElement, LaplaceReproducesAffineMotions) {
  const Mesh m = mesh();
  const Topology topo = build_topology(m);
  for (const auto& [name, map] : affine_maps(m.dim)) {
    SCOPED_TRACE(name);
    const BaselineResult r = laplace_morph(m, topo, boundary_moved_by(m, topo, map), cholesky());
    EXPECT_EQ(r.linear_solves, 1);
    EXPECT_TRUE(r.linear.ok) << r.linear.message;
    EXPECT_LT(max_error(r.x, m, map), 1e-10);
  }
}

// Plain linear elasticity (χ = 0) has constant coefficients, so any affine displacement —
// the one of a rotation included, although its strain sym(R − I) is not zero — has constant
// stress and is in equilibrium: it is reproduced exactly.
TEST_P(BaselinesByElement, ElasticWithoutStiffeningReproducesAffineMotions) {
  const Mesh m = mesh();
  const Topology topo = build_topology(m);
  for (const auto& [name, map] : affine_maps(m.dim)) {
    SCOPED_TRACE(name);
    const BaselineResult r = elastic_morph(m, topo, boundary_moved_by(m, topo, map), cholesky(0.0));
    EXPECT_LT(max_error(r.x, m, map), 1e-10);
  }
}

// With stiffening the coefficient (J₀/J)^χ varies over the perturbed mesh: only a motion with
// zero strain — a translation — stays exact (a rotation has strain sym(R − I) ≠ 0 in linear
// elasticity, so it is not exact, see StiffenedElasticBendsAffineMotionsOnNonuniformMeshes).
TEST_P(BaselinesByElement, StiffenedElasticReproducesTranslations) {
  const Mesh m = mesh();
  const Topology topo = build_topology(m);
  const Map map = affine_maps(m.dim)[0].second;
  const BaselineResult r = elastic_morph(m, topo, boundary_moved_by(m, topo, map), cholesky(2.0));
  EXPECT_LT(max_error(r.x, m, map), 1e-10);
}

// Kernel of the stiffness: constants per component (laplace), and the translations and the
// infinitesimal rotations (elastic), on every cell type and order.
TEST_P(BaselinesByElement, StiffnessAnnihilatesItsKernel) {
  const Mesh m = mesh();
  const Topology topo = build_topology(m);
  const int d = m.dim;
  const auto n = static_cast<Eigen::Index>(m.n_nodes());
  detail::StiffnessParams p;
  const Eigen::SparseMatrix<double> L = detail::assemble_stiffness(m, topo, p, "laplace");
  p = {detail::StiffnessKind::Elastic, 0.6, 0.4, 1.5, 0};
  const Eigen::SparseMatrix<double> E = detail::assemble_stiffness(m, topo, p, "elastic");
  for (const auto* K : {&L, &E}) {
    EXPECT_EQ(K->rows(), d * n);
    EXPECT_EQ((Eigen::SparseMatrix<double>(K->transpose()) - *K).norm(), 0.0);  // exactly symmetric
    for (int k = 0; k < d; ++k) {
      Eigen::MatrixXd u = Eigen::MatrixXd::Zero(d, n);
      u.row(k).setOnes();
      EXPECT_LT((*K * u.reshaped()).norm(), 1e-11 * K->norm());
    }
  }
  Eigen::MatrixXd W = Eigen::MatrixXd::Zero(d, d);  // a skew matrix: u = W x is a rotation mode
  W(0, 1) = 1.0;
  W(1, 0) = -1.0;
  const Eigen::MatrixXd u = W * m.x;
  EXPECT_LT((E * u.reshaped()).norm(), 1e-11 * E.norm());
  EXPECT_GT((L * u.reshaped()).norm(), 1e-3 * L.norm());  // Laplace: W x is harmonic, but its normal flux loads the boundary rows
}

INSTANTIATE_TEST_SUITE_P(All, BaselinesByElement, ::testing::ValuesIn(test::all_cell_cases()), test::CaseName{});
INSTANTIATE_TEST_SUITE_P(PrismPyramid, BaselinesByElement, ::testing::ValuesIn(test::prism_pyramid_cases()), test::CaseName{});

// Meshes above the size at which assembly goes parallel (512 cells per block).
TEST(BaselineStiffness, AssemblyIsBitwiseIdenticalForAnyThreadCount) {
  for (const auto& [type, order, n] : {std::tuple{ElementType::Triangle, 2, 20}, std::tuple{ElementType::Tetrahedron, 1, 6},
                                       std::tuple{ElementType::Hexahedron, 2, 8}}) {
    SCOPED_TRACE(name_of(type));
    const Mesh m = perturbed_mesh(type, order, n);
    ASSERT_GE(m.n_cells(), 512u);
    const Topology topo = build_topology(m);
    detail::StiffnessParams p{detail::StiffnessKind::Elastic, 0.6, 0.4, 1.0, 1};
    const Eigen::SparseMatrix<double> K1 = detail::assemble_stiffness(m, topo, p, "elastic");
    p.threads = 3;
    const Eigen::SparseMatrix<double> K3 = detail::assemble_stiffness(m, topo, p, "elastic");
    ASSERT_EQ(K1.nonZeros(), K3.nonZeros());
    EXPECT_EQ((K1 - K3).norm(), 0.0);
  }
}

// The textbook P1 stiffness of the right triangle (0,0), (1,0), (0,1): [[1, −½, −½], [−½, ½, 0], [−½, 0, ½]].
TEST(LaplaceStiffness, MatchesTheClosedFormOnOneTriangle) {
  Mesh m;
  m.dim = 2;
  m.x = (Eigen::MatrixXd(2, 3) << 0, 1, 0, 0, 0, 1).finished();
  m.cells.push_back({});
  const std::int32_t tri[3] = {0, 1, 2};
  m.cells[0].push_back(tri, 1);
  const Eigen::MatrixXd K(detail::assemble_stiffness(m, build_topology(m), {}, "laplace"));
  const Eigen::Matrix3d expected{{1, -0.5, -0.5}, {-0.5, 0.5, 0}, {-0.5, 0, 0.5}};
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b)
      for (int k = 0; k < 2; ++k)
        for (int l = 0; l < 2; ++l) EXPECT_NEAR(K(2 * a + k, 2 * b + l), k == l ? expected(a, b) : 0.0, 1e-15);
}

// Fixed nodes keep their input position and Prescribed nodes land on their target bit for bit,
// for a motion no affine map explains (the top side bulges).
TEST(Baselines, FixedNodesStayAndPrescribedNodesReachTheirTargets) {
  const Mesh m = perturbed_mesh(ElementType::Triangle, 2, 4);
  const Topology topo = build_topology(m);
  BoundaryTargets bc = free_targets(m);
  for (std::int32_t j : boundary_nodes(m, topo)) bc.role[static_cast<std::size_t>(j)] = NodeRole::Fixed;
  for (std::int32_t j : boundary_nodes(m, topo))
    if (m.x(1, j) > 1.0 - 1e-12)
      prescribe(bc, m, j, [](const Eigen::VectorXd& x) -> Eigen::VectorXd {
        return x + Eigen::Vector2d(0.0, 0.2 * std::sin(std::numbers::pi * x[0]));
      });
  for (const bool elastic : {false, true}) {
    const BaselineResult r = elastic ? elastic_morph(m, topo, bc, cholesky(1.0)) : laplace_morph(m, topo, bc, cholesky());
    double interior_motion = 0.0;
    for (std::size_t j = 0; j < m.n_nodes(); ++j) {
      const auto c = static_cast<Eigen::Index>(j);
      if (bc.role[j] == NodeRole::Fixed) {
        EXPECT_TRUE((r.x.col(c).array() == m.x.col(c).array()).all()) << j;
      }
      if (bc.role[j] == NodeRole::Prescribed) {
        EXPECT_TRUE((r.x.col(c).array() == bc.target.col(c).array()).all()) << j;
      }
      if (bc.role[j] == NodeRole::Free) interior_motion = std::max(interior_motion, (r.x.col(c) - m.x.col(c)).norm());
    }
    EXPECT_GT(interior_motion, 0.05);  // the interior follows the bulge
    EXPECT_LT(interior_motion, 0.2);   // and the maximum principle holds (laplace), roughly so (elastic)
    Mesh out = m;
    out.x = r.x;
    EXPECT_EQ(count_invalid_cells(out), 0u);
  }
}

// A cube or square turned by a general rotation R: the sides whose normals are R·e_y (and R·e_z)
// slide, the two others translate along R·e_x. The exact answer is that translation everywhere,
// and it needs the tangential motion of the slide nodes, so n·u = 0 is met without pinning them.
void expect_sliding_translation(ElementType type, int order) {
  Mesh m = perturbed_mesh(type, order, 3);
  const int d = m.dim;
  const Eigen::MatrixXd R = rotation(d, 25.0);
  m.x = R * m.x;
  const Topology topo = build_topology(m);
  const Eigen::VectorXd shift = 0.15 * R.col(0);
  const Map map = [shift](const Eigen::VectorXd& x) -> Eigen::VectorXd { return x + shift; };
  BoundaryTargets bc = free_targets(m);
  for (std::int32_t j : boundary_nodes(m, topo)) {
    const Eigen::VectorXd xi = R.transpose() * m.x.col(j);  // position in the unrotated cube
    if (xi[0] < 1e-9 || xi[0] > 1.0 - 1e-9) {
      prescribe(bc, m, j, map);
      continue;
    }
    bc.role[static_cast<std::size_t>(j)] = NodeRole::Slide;
    for (int k = 1; k < d; ++k)
      if (xi[k] < 1e-9 || xi[k] > 1.0 - 1e-9) bc.normal.col(j) = R.col(k);
  }
  for (const bool elastic : {false, true}) {
    SCOPED_TRACE(elastic ? "elastic" : "laplace");
    const BaselineResult r = elastic ? elastic_morph(m, topo, bc, cholesky(1.0)) : laplace_morph(m, topo, bc, cholesky());
    EXPECT_LT(max_error(r.x, m, map), 1e-10);
    for (std::int32_t j : bc.nodes_with(NodeRole::Slide))
      EXPECT_LT(std::abs(bc.normal.col(j).dot(r.x.col(j) - m.x.col(j))), 1e-13);
  }
}

TEST(Baselines, SlideNodesMoveOnlyTangentially2D) { expect_sliding_translation(ElementType::Quadrilateral, 2); }
TEST(Baselines, SlideNodesMoveOnlyTangentially3D) { expect_sliding_translation(ElementType::Tetrahedron, 2); }

// Sliding with a non-uniform solution: the bottom slides, the top is sheared, the sides are free.
// n·u stays zero at every slide node while they move along the plane.
TEST(Baselines, SlideNodesKeepZeroNormalDisplacementUnderShear) {
  const Mesh m = perturbed_mesh(ElementType::Hexahedron, 2, 2);
  const Topology topo = build_topology(m);
  BoundaryTargets bc = free_targets(m);
  const Eigen::Vector3d n(0.0, 0.0, 1.0);
  for (std::int32_t j : boundary_nodes(m, topo)) {
    if (m.x(2, j) < 1e-12) {
      bc.role[static_cast<std::size_t>(j)] = NodeRole::Slide;
      bc.normal.col(j) = -n;
    } else if (m.x(2, j) > 1.0 - 1e-12) {
      prescribe(bc, m, j, [](const Eigen::VectorXd& x) -> Eigen::VectorXd {
        return x + Eigen::Vector3d(0.2 * x[1], 0.1 * x[0] * x[0], 0.05);
      });
    }
  }
  for (const bool elastic : {false, true}) {
    const BaselineResult r = elastic ? elastic_morph(m, topo, bc, cholesky(1.0)) : laplace_morph(m, topo, bc, cholesky());
    double tangential = 0.0;
    for (std::int32_t j : bc.nodes_with(NodeRole::Slide)) {
      const Eigen::Vector3d u = r.x.col(j) - m.x.col(j);
      EXPECT_LT(std::abs(n.dot(u)), 1e-14);
      tangential = std::max(tangential, u.norm());
    }
    EXPECT_GT(tangential, 1e-2);
  }
}

// The point of the baseline: an inner square turned by 120° inside a fixed outer square. The
// Laplacian spreads the rotation linearly over the gap and folds the cells there.
TEST(LaplaceMorph, LargeInnerRotationInvertsCells) {
  for (ElementType type : {ElementType::Quadrilateral, ElementType::Triangle}) {
    const Mesh m = structured_mesh(type, 1, 12);
    const Topology topo = build_topology(m);
    const Eigen::Vector2d c(0.5, 0.5);
    const Eigen::Matrix2d R = rotation(2, 120.0);
    BoundaryTargets bc = free_targets(m);
    for (std::int32_t j : boundary_nodes(m, topo)) bc.role[static_cast<std::size_t>(j)] = NodeRole::Fixed;
    for (Eigen::Index j = 0; j < m.x.cols(); ++j)
      if ((m.x.col(j) - c).lpNorm<Eigen::Infinity>() < 1.0 / 6.0 + 1e-9)
        prescribe(bc, m, static_cast<std::int32_t>(j),
                  [&](const Eigen::VectorXd& x) -> Eigen::VectorXd { return c + R * (x - c); });
    ASSERT_EQ(count_invalid_cells(m), 0u);
    const BaselineResult r = laplace_morph(m, topo, bc, cholesky());
    Mesh out = m;
    out.x = r.x;
    EXPECT_GT(count_invalid_cells(out), 0u) << name_of(type);
  }
}

// Stiffening makes small cells stiff: on a mesh graded towards x = 0, a side shifted along y
// strains the small cells next to it less when χ grows.
TEST(ElasticMorph, StiffeningProtectsSmallCells) {
  Mesh m = structured_mesh(ElementType::Quadrilateral, 1, 8);
  m.x.row(0) = m.x.row(0).array().square().matrix();  // first column of cells 64x thinner than the last
  const Topology topo = build_topology(m);
  BoundaryTargets bc = free_targets(m);
  for (Eigen::Index j = 0; j < m.x.cols(); ++j) {
    if (m.x(0, j) < 1e-12) prescribe(bc, m, static_cast<std::int32_t>(j), [](const Eigen::VectorXd& x) -> Eigen::VectorXd {
      return x + Eigen::Vector2d(0.0, 0.1);
    });
    if (m.x(0, j) > 1.0 - 1e-12) bc.role[static_cast<std::size_t>(j)] = NodeRole::Fixed;
  }
  // Shear strain across the first column of cells, on the middle row (nodes at x = 0 and x = 1/64).
  auto first_column_strain = [&](double chi) {
    const BaselineResult r = elastic_morph(m, topo, bc, cholesky(chi));
    double u0 = 0.0, u1 = 0.0;
    for (Eigen::Index j = 0; j < m.x.cols(); ++j)
      if (std::abs(m.x(1, j) - 0.5) < 1e-12) {
        if (m.x(0, j) < 1e-12) u0 = r.x(1, j) - m.x(1, j);
        if (std::abs(m.x(0, j) - 1.0 / 64.0) < 1e-12) u1 = r.x(1, j) - m.x(1, j);
      }
    return std::abs(u0 - u1) * 64.0;
  };
  const double s0 = first_column_strain(0.0), s1 = first_column_strain(1.0), s2 = first_column_strain(2.0);
  // No stiffening: close to the mean shear 0.1 of the strip (0.072 when written: the free top
  // and bottom sides relax it); each step of χ cuts the strain of the thin cells about tenfold.
  EXPECT_NEAR(s0, 0.1, 0.05);
  EXPECT_LT(s1, 0.2 * s0);
  EXPECT_LT(s2, 0.2 * s1);
}

// With χ > 0 on a mesh of unequal cells, a non-rigid affine motion is not in equilibrium any more.
TEST(ElasticMorph, StiffenedElasticBendsAffineMotionsOnNonuniformMeshes) {
  const Mesh m = perturbed_mesh(ElementType::Triangle, 1, 4);
  const Topology topo = build_topology(m);
  const Map map = affine_maps(2)[2].second;
  const BaselineResult r = elastic_morph(m, topo, boundary_moved_by(m, topo, map), cholesky(2.0));
  EXPECT_GT(max_error(r.x, m, map), 1e-5);
}

TEST(Baselines, EveryNodeConstrainedNeedsNoSolve) {
  const Mesh m = structured_mesh(ElementType::Quadrilateral, 2, 2);
  BoundaryTargets bc = free_targets(m);
  for (Eigen::Index j = 0; j < m.x.cols(); ++j) prescribe(bc, m, static_cast<std::int32_t>(j), affine_maps(2)[1].second);
  const BaselineResult r = laplace_morph(m, build_topology(m), bc, cholesky());
  EXPECT_EQ(r.linear_solves, 0);
  EXPECT_TRUE(r.x == bc.target);
}

TEST(Baselines, SingularSystemsAreInputErrors) {
  const Mesh m = structured_mesh(ElementType::Triangle, 1, 3);
  const Topology topo = build_topology(m);
  const BoundaryTargets bc = free_targets(m);  // nothing holds the mesh
  EXPECT_THROW(laplace_morph(m, topo, bc, cholesky()), InputError);
  EXPECT_THROW(elastic_morph(m, topo, bc, cholesky()), InputError);
  BoundaryTargets one = bc;  // one fixed node leaves elasticity a rotation
  one.role[0] = NodeRole::Fixed;
  EXPECT_NO_THROW(laplace_morph(m, topo, one, cholesky()));
  EXPECT_THROW(elastic_morph(m, topo, one, cholesky()), InputError);
  BoundaryTargets slides = bc;  // slide planes of one normal: the motion along them is free
  for (std::int32_t j : boundary_nodes(m, topo)) {
    slides.role[static_cast<std::size_t>(j)] = NodeRole::Slide;
    slides.normal.col(j) = Eigen::Vector2d(0.0, 1.0);
  }
  EXPECT_THROW(laplace_morph(m, topo, slides, cholesky()), InputError);
  slides.normal.col(0) = Eigen::Vector2d(1.0, 0.0);  // one other normal anchors the translations
  EXPECT_NO_THROW(laplace_morph(m, topo, slides, cholesky()));
}

TEST(Baselines, InvalidInputIsAnInputError) {
  const Mesh good = structured_mesh(ElementType::Quadrilateral, 1, 3);
  const Topology topo = build_topology(good);
  BoundaryTargets bc = free_targets(good);
  for (std::int32_t j : boundary_nodes(good, topo)) bc.role[static_cast<std::size_t>(j)] = NodeRole::Fixed;
  Mesh folded = good;
  Eigen::Index inner = 0;
  while (bc.role[static_cast<std::size_t>(inner)] != NodeRole::Free) ++inner;
  folded.x(0, inner) += 0.8;  // an interior node pushed through its neighbours
  EXPECT_THROW(laplace_morph(folded, topo, bc, cholesky()), InputError);
  BoundaryTargets no_normal = bc;
  no_normal.role[1] = NodeRole::Slide;  // a slide node without a normal
  EXPECT_THROW(laplace_morph(good, topo, no_normal, cholesky()), InputError);
  BaselineOptions o = cholesky();
  o.poisson_ratio = 0.5;
  EXPECT_THROW(elastic_morph(good, topo, bc, o), InputError);
  o = cholesky(-1.0);
  EXPECT_THROW(elastic_morph(good, topo, bc, o), InputError);
}

// The iterative backend gives the same answer to its tolerance.
TEST(Baselines, IterativeSolverAgreesWithCholesky) {
  const Mesh m = perturbed_mesh(ElementType::Tetrahedron, 2, 3);
  const Topology topo = build_topology(m);
  const BoundaryTargets bc = boundary_moved_by(m, topo, affine_maps(3)[2].second);
  BaselineOptions o = cholesky(1.0);
  const BaselineResult direct = elastic_morph(m, topo, bc, o);
  o.solver = LinearSolverKind::Iterative;
  const BaselineResult iterative = elastic_morph(m, topo, bc, o);
  EXPECT_TRUE(iterative.linear.ok) << iterative.linear.message;
  EXPECT_GT(iterative.linear.iterations, 0);
  EXPECT_LT((direct.x - iterative.x).cwiseAbs().maxCoeff(), 1e-7);
}

}  // namespace
}  // namespace meshmorph
