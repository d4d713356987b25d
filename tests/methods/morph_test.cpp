// SPDX-License-Identifier: MIT
#include "meshmorph/methods/morph.h"

#include <cmath>
#include <numbers>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "meshmorph/error.h"
#include "meshmorph/fem/elevate.h"
#include "meshmorph/fem/jacobian.h"
#include "meshmorph/fem/structured.h"
#include "meshmorph/fem/trace.h"
#include "meshmorph/fem/validity.h"
#include "meshmorph/io/mesh_io.h"
#include "meshmorph/quality/element_quality.h"
#include "methods/morph_fixtures.h"

namespace meshmorph {
namespace {

using test::min_quality;

// x ↦ s R x + t: a rotation about a skew axis (3D) or by 35° (2D), scaled and translated.
Eigen::MatrixXd similarity(const Eigen::MatrixXd& x) {
  const int d = static_cast<int>(x.rows());
  Eigen::MatrixXd R;
  if (d == 2) {
    const double a = 35.0 * M_PI / 180.0;
    R = Eigen::Rotation2Dd(a).toRotationMatrix();
  } else {
    R = Eigen::AngleAxisd(0.6, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  }
  Eigen::VectorXd t = Eigen::VectorXd::LinSpaced(d, 0.3, -0.2);
  return ((1.3 * R * x).colwise() + t).eval();
}

BoundaryTargets all_boundary(const Mesh& mesh, const Topology& topo, const Eigen::MatrixXd& target) {
  BoundaryTargets bc;
  bc.role.assign(mesh.n_nodes(), NodeRole::Free);
  bc.target = mesh.x;
  bc.normal = Eigen::MatrixXd::Zero(mesh.dim, static_cast<Eigen::Index>(mesh.n_nodes()));
  for (std::int32_t node : boundary_nodes(mesh, topo)) {
    bc.role[node] = NodeRole::Prescribed;
    bc.target.col(node) = target.col(node);
  }
  return bc;
}

struct Case {
  ElementType type;
  int order;
  int n;
};

// Morphs structured_mesh(type, order, n) with its whole boundary moved by similarity() and
// checks the result: converged, the interior within `tolerance` of the similarity, quality 1.
// Returns the Krylov iterations.
long long check_similarity(const Mesh& mesh, LinearSolverKind solver, double tolerance) {
  const Topology topo = build_topology(mesh);
  const Eigen::MatrixXd exact = similarity(mesh.x);
  const BoundaryTargets bc = all_boundary(mesh, topo, exact);
  MorphOptions o;
  o.tolerance = 1e-13;
  o.solver = solver;
  Morpher morpher(mesh, topo, bc, o);
  Eigen::MatrixXd x = mesh.x;
  const MorphResult r = morpher.solve(bc.target, x);
  EXPECT_TRUE(r.converged) << r.message;
  EXPECT_LT((x - exact).cwiseAbs().maxCoeff(), tolerance);
  EXPECT_NEAR(min_quality(mesh, x), 1.0, 1e-10);
  return r.krylov;
}

long long check_similarity(ElementType type, int order, int n, LinearSolverKind solver, double tolerance) {
  return check_similarity(structured_mesh(type, order, n), solver, tolerance);
}

class MorphAffine : public ::testing::TestWithParam<Case> {};

// Exactness: a similarity of the whole boundary is reproduced in the interior, quality 1.
TEST_P(MorphAffine, ReproducesASimilarityOfTheBoundaryExactly) {
  const Case c = GetParam();
  check_similarity(c.type, c.order, c.n, LinearSolverKind::Cholesky, 1e-10);
}

INSTANTIATE_TEST_SUITE_P(
    EveryTypeAndOrder, MorphAffine,
    ::testing::Values(Case{ElementType::Triangle, 1, 4}, Case{ElementType::Triangle, 2, 3}, Case{ElementType::Triangle, 3, 2},
                      Case{ElementType::Triangle, 4, 2}, Case{ElementType::Quadrilateral, 1, 4},
                      Case{ElementType::Quadrilateral, 2, 3}, Case{ElementType::Quadrilateral, 3, 2},
                      Case{ElementType::Tetrahedron, 1, 3}, Case{ElementType::Tetrahedron, 2, 2},
                      Case{ElementType::Tetrahedron, 3, 1}, Case{ElementType::Tetrahedron, 4, 1},
                      Case{ElementType::Hexahedron, 1, 3}, Case{ElementType::Hexahedron, 2, 2},
                      Case{ElementType::Hexahedron, 3, 1}),
    [](const ::testing::TestParamInfo<Case>& param) {
      return std::string(name_of(param.param.type)) + "_p" + std::to_string(param.param.order);
    });
INSTANTIATE_TEST_SUITE_P(
    PrismPyramid, MorphAffine,
    ::testing::Values(Case{ElementType::Prism, 1, 3}, Case{ElementType::Prism, 2, 2}, Case{ElementType::Pyramid, 1, 2}),
    [](const ::testing::TestParamInfo<Case>& param) {
      return std::string(name_of(param.param.type)) + "_p" + std::to_string(param.param.order);
    });

// A Gmsh mesh of prisms and hexahedra in a thin layer under tetrahedra, with pyramids between
// (tests/data/hybrid_layer.geo): the similarity of its boundary is reproduced inside, at
// quality 1 (to 1e-8: the layer's cells are 15 times wider than thick).
TEST(Morph, AHybridLayerMeshFollowsASimilarity) {
  const Mesh mesh = read_mesh(std::string(MESHMORPH_TEST_DATA) + "/hybrid_layer.msh");
  ASSERT_EQ(mesh.cells.size(), 4u);
  check_similarity(mesh, LinearSolverKind::Cholesky, 1e-8);
}

// The iterative backend on high-order meshes (over 500 unknowns, so that the vertex hats
// are a level of their own, detail::make_newton_solver): the same similarity. Newton stops
// at the decrement δ* with CG's solutions, not at a direct solve's exact step: the interior
// is reached to ~1e-7, the quality to second order in that.
TEST(Morph, IterativeSolverWithVertexHatsReproducesASimilarity) {
  EXPECT_GT(check_similarity(ElementType::Tetrahedron, 2, 4, LinearSolverKind::Iterative, 1e-6), 0);  // 1029 unknowns
}

// Sliding nodes keep their plane and move along it: the left and right sides translate by
// 0.2 in x, the bottom and top slide on y = const, so the exact answer is the translation.
TEST(Morph, SlidingNodesFollowATranslationAlongTheirPlane) {
  const Mesh mesh = structured_mesh(ElementType::Triangle, 2, 4);
  const Topology topo = build_topology(mesh);
  Eigen::MatrixXd exact = mesh.x;
  exact.row(0).array() += 0.2;
  BoundaryTargets bc = all_boundary(mesh, topo, exact);
  for (std::int32_t node : boundary_nodes(mesh, topo)) {
    const double y = mesh.x(1, node), x = mesh.x(0, node);
    if ((y < 1e-12 || y > 1 - 1e-12) && x > 1e-12 && x < 1 - 1e-12) {
      bc.role[node] = NodeRole::Slide;
      bc.target.col(node) = mesh.x.col(node);
      bc.normal.col(node) = Eigen::Vector2d(0, 1);
    }
  }
  MorphOptions o;
  o.tolerance = 1e-13;
  Morpher morpher(mesh, topo, bc, o);
  Eigen::MatrixXd x = mesh.x;
  const MorphResult r = morpher.solve(bc.target, x);
  ASSERT_TRUE(r.converged) << r.message;
  EXPECT_LT((x - exact).cwiseAbs().maxCoeff(), 1e-10);
}

// Slide nodes on oblique planes: the unit square (cube) rotated off the axes, its left side
// pushed 0.2 towards the right one (the other nodes of both sides and of the edges prescribed
// to the affine compression), the nodes inside the sides (faces) y = 0, 1 (and z = 0, 1 in 3D)
// sliding. They end on their planes to rounding, having slid, and the mesh is valid.
void check_oblique_slide(ElementType type, int order, int n) {
  const Mesh reference = structured_mesh(type, order, n);
  const int d = reference.dim;
  Eigen::MatrixXd R;
  if (d == 2)
    R = Eigen::Rotation2Dd(35.0 * M_PI / 180.0).toRotationMatrix();
  else
    R = Eigen::AngleAxisd(1.0, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  Mesh mesh = reference;
  mesh.x = R * reference.x;
  const Topology topo = build_topology(mesh);
  Eigen::MatrixXd compressed = reference.x;
  compressed.row(0) = (0.2 + 0.8 * reference.x.row(0).array()).matrix();
  BoundaryTargets bc = all_boundary(mesh, topo, R * compressed);
  std::vector<std::int32_t> sliding;
  for (std::int32_t node : boundary_nodes(mesh, topo)) {
    const Eigen::VectorXd u = reference.x.col(node);
    const auto on_side = [](double v) { return v < 1e-12 || v > 1 - 1e-12; };
    int sides = 0, axis = 0;
    for (int k = 0; k < d; ++k)
      if (on_side(u[k])) ++sides, axis = k;
    if (sides != 1 || axis == 0) continue;
    bc.role[node] = NodeRole::Slide;
    bc.target.col(node) = mesh.x.col(node);
    bc.normal.col(node) = R.col(axis);
    sliding.push_back(node);
  }
  for (int k = 1; k < d; ++k) ASSERT_LT(R.col(k).cwiseAbs().maxCoeff(), 0.9);  // the slide normals are oblique
  ASSERT_FALSE(sliding.empty());
  Morpher morpher(mesh, topo, bc, MorphOptions{});
  Eigen::MatrixXd x = mesh.x;
  const MorphResult r = morpher.solve(bc.target, x);
  ASSERT_TRUE(r.converged) << r.message;
  double off = 0.0, slid = 0.0;
  for (std::int32_t node : sliding) {
    off = std::max(off, std::abs(bc.normal.col(node).dot(x.col(node) - mesh.x.col(node))));
    slid = std::max(slid, (x.col(node) - mesh.x.col(node)).norm());
  }
  EXPECT_LT(off, 1e-12);
  EXPECT_GT(slid, 0.05);
  Mesh moved = mesh;
  moved.x = x;
  EXPECT_EQ(count_invalid_cells(moved), 0u);
}

TEST(Morph, SlideNodesStayOnObliquePlanes2D) { check_oblique_slide(ElementType::Triangle, 2, 4); }
TEST(Morph, SlideNodesStayOnObliquePlanes3D) { check_oblique_slide(ElementType::Tetrahedron, 1, 3); }

// A time series in 4 steps ends where one step does (the minimiser is unique), and the
// history has a row per augmented-Lagrangian iteration of every step.
TEST(Morph, StepsReachTheSameSimilarity) {
  const Mesh mesh = structured_mesh(ElementType::Quadrilateral, 1, 4);
  const Topology topo = build_topology(mesh);
  const Eigen::MatrixXd exact = similarity(mesh.x);
  const BoundaryTargets bc = all_boundary(mesh, topo, exact);
  MorphOptions o;
  o.tolerance = 1e-13;
  Morpher morpher(mesh, topo, bc, o);
  Eigen::MatrixXd x = mesh.x;
  std::size_t rows = 0;
  for (int s = 1; s <= 4; ++s) {
    const Eigen::MatrixXd g = mesh.x + (s / 4.0) * (exact - mesh.x);  // a linear path
    const MorphResult r = morpher.solve(g, x, s);
    ASSERT_TRUE(r.converged) << "step " << s << ": " << r.message;
    EXPECT_EQ(r.history.front().step, s);
    rows += r.history.size();
  }
  EXPECT_GE(rows, 4u);
  EXPECT_LT((x - exact).cwiseAbs().maxCoeff(), 1e-10);
}

// With one augmented-Lagrangian iteration the boundary is not reached: not converged, a
// message, and the coordinates are still a valid mesh.
TEST(Morph, AnExhaustedBudgetReportsWhyAndLeavesAValidMesh) {
  const Mesh mesh = structured_mesh(ElementType::Triangle, 1, 6);
  const Topology topo = build_topology(mesh);
  const BoundaryTargets bc = all_boundary(mesh, topo, similarity(mesh.x));
  MorphOptions o;
  o.max_outer = 1;
  Morpher morpher(mesh, topo, bc, o);
  Eigen::MatrixXd x = mesh.x;
  const MorphResult r = morpher.solve(bc.target, x);
  EXPECT_FALSE(r.converged);
  EXPECT_NE(r.message.find("augmented-Lagrangian iterations"), std::string::npos) << r.message;
  Mesh moved = mesh;
  moved.x = x;
  EXPECT_EQ(count_invalid_cells(moved), 0u);
}

// The sphere-in-a-box P2 mesh (examples/meshes) with the sphere (r = 0.4) translated by 0.5
// towards the box's face at x = 1. Measured at its quadrature points alone, the energy lets
// cells next to the sphere fold at a node while every quadrature point stays positive: the
// line search then meets the dense validity test's wall and the run stalls (13 AL iterations,
// boundary error stuck). With the cells that block a search guarded at their validity
// samples (energy/validity_guard.h), it reaches the boundary and stays valid.
TEST(Morph, GuardedCellsLetAP2MeshFollowALargeTranslation) {
  const Mesh mesh = read_mesh(std::string(MESHMORPH_TEST_DATA) + "/../../examples/meshes/sphere_in_box_p2.msh");
  const Topology topo = build_topology(mesh);
  const BoundaryTargets bc = test::translated_group(mesh, "box", "sphere", 0.5);
  Morpher morpher(mesh, topo, bc, MorphOptions{});
  Eigen::MatrixXd x = mesh.x;
  const MorphResult r = morpher.solve(bc.target, x);
  EXPECT_TRUE(r.converged) << r.message;
  EXPECT_GT(r.guarded_cells, 0u);
  EXPECT_LT(r.guarded_cells, mesh.n_cells() / 10);  // the cells that blocked a search, not the mesh
  Mesh moved = mesh;
  moved.x = x;
  EXPECT_EQ(count_invalid_cells(moved), 0u);
  EXPECT_LT(r.history.back().boundary_error_max, 1e-9 * 2 * std::sqrt(3.0));
  EXPECT_GT(min_quality(mesh, x), 0.4);
}

// An annulus (examples/meshes/annulus.geo at lc = 0.2: 196 nodes) at P2, its inner circle
// turned by 140°: line searches meet cells that are valid at their quadrature points and not
// at their nodes. "ring" guards every cell that shares a node with such a cell, "auto" does so
// in 2D; both variants reach the boundary with a valid mesh.
// tests/data/annulus_coarse.msh's inner circle turned by `degrees`, its outer circle fixed.
BoundaryTargets turned_annulus(const Mesh& mesh, double degrees) {
  BoundaryTargets bc;
  bc.role.assign(mesh.n_nodes(), NodeRole::Free);
  bc.target = mesh.x;
  bc.normal = Eigen::MatrixXd::Zero(2, static_cast<Eigen::Index>(mesh.n_nodes()));
  const double turn = degrees * std::numbers::pi / 180.0;
  for (std::int32_t node : mesh.group_nodes(*mesh.find_group("outer"))) bc.role[node] = NodeRole::Fixed;
  for (std::int32_t node : mesh.group_nodes(*mesh.find_group("inner"))) {
    bc.role[node] = NodeRole::Prescribed;
    bc.target.col(node) = Eigen::Rotation2Dd(turn) * mesh.x.col(node).head<2>();
  }
  return bc;
}

// The inner circle of an annulus translated by 0.3: with μ raised after every multiplier
// update that leaves the boundary short, the augmented Lagrangian reaches it in at most 5
// iterations; with μ kept while c ≤ ε_k (about Algorithm 1 as printed) the updates at μ₀
// crawl. The same mesh either way, to the tolerance's order, with the weights grown by β at
// every update (with adaptive growth the two schedules take the weights along paths of their
// own, and the meshes differ by 1.2e-3 in min quality).
TEST(Morph, RaisingMuAfterMultiplierUpdatesReachesTheBoundaryInFewerIterations) {
  const Mesh mesh = read_mesh(std::string(MESHMORPH_TEST_DATA) + "/annulus_coarse.msh");
  const Topology topo = build_topology(mesh);
  BoundaryTargets bc = turned_annulus(mesh, 0.0);
  for (std::int32_t node : mesh.group_nodes(*mesh.find_group("inner"))) bc.target(0, node) += 0.3;
  long long outer[2];
  Eigen::MatrixXd x[2];
  for (const int k : {0, 1}) {
    MorphOptions o;
    o.min_decrease = k == 0 ? 0.0 : 1.0;
    o.adaptive_growth = false;
    x[k] = mesh.x;
    const MorphResult r = Morpher(mesh, topo, bc, o).solve(bc.target, x[k]);
    ASSERT_TRUE(r.converged) << o.min_decrease << ": " << r.message;
    outer[k] = r.outer;
  }
  EXPECT_LE(outer[0], 5);
  EXPECT_GE(outer[1], outer[0] + 2);
  EXPECT_NEAR(min_quality(mesh, x[0]), min_quality(mesh, x[1]), 1e-3);
}

TEST(Morph, InTwoDimensionsTheGuardTakesTheRingAroundABlockingCell) {
  const Mesh linear = read_mesh(std::string(MESHMORPH_TEST_DATA) + "/annulus_coarse.msh");
  const Mesh mesh = elevate_order(linear, 2);
  const Topology topo = build_topology(mesh);
  const BoundaryTargets bc = turned_annulus(mesh, 140.0);
  std::size_t guarded[3] = {};
  const MorphOptions::Guard kinds[3] = {MorphOptions::Guard::Cells, MorphOptions::Guard::Ring, MorphOptions::Guard::Auto};
  for (int k = 0; k < 3; ++k) {
    MorphOptions o;
    o.guard = kinds[k];
    Eigen::MatrixXd x = mesh.x;
    const MorphResult r = Morpher(mesh, topo, bc, o).solve(bc.target, x);
    ASSERT_TRUE(r.converged) << k << ": " << r.message;
    EXPECT_FALSE(r.finish.has_value()) << k;
    Mesh moved = mesh;
    moved.x = x;
    EXPECT_EQ(count_invalid_cells(moved), 0u) << k;
    guarded[k] = r.guarded_cells;
  }
  EXPECT_GT(guarded[0], 0u);
  EXPECT_GT(guarded[1], guarded[0]);
  EXPECT_EQ(guarded[2], guarded[1]);
}

// Algorithm 2 with at most four Newton steps between weight updates against the paper's
// loop, where every solve meets δ: on a turn of 150° each re-solve after an update took ~9
// damped steps, and the cut-short loop reaches about the same quality (0.113 against 0.118)
// with half the Newton steps (770 against 1519).
TEST(Morph, CutShortSolvesBetweenWeightUpdatesKeepTheQualityForHalfTheSteps) {
  const Mesh mesh = read_mesh(std::string(MESHMORPH_TEST_DATA) + "/annulus_coarse.msh");
  const Topology topo = build_topology(mesh);
  const BoundaryTargets bc = turned_annulus(mesh, 150.0);
  double quality[2];
  long long steps[2];
  for (const int k : {0, 1}) {
    MorphOptions o;
    o.weight_steps = k == 0 ? 0 : 4;
    Eigen::MatrixXd x = mesh.x;
    const MorphResult r = Morpher(mesh, topo, bc, o).solve(bc.target, x);
    ASSERT_TRUE(r.converged) << o.weight_steps << ": " << r.message;
    EXPECT_FALSE(r.finish.has_value());
    quality[k] = min_quality(mesh, x);
    steps[k] = r.newton;
  }
  EXPECT_GT(quality[0], 0.1);
  EXPECT_GT(quality[1], 0.9 * quality[0]);
  EXPECT_LT(10 * steps[1], 7 * steps[0]);
}

// Paper 000 §5.3, small: bench/geo/bl_circle_2d.geo at h_wall 0.8, h_far 5, h_first 1e-4
// (tests/data/bl_circle_coarse.msh, 275 nodes, first-layer stretching 1 : 8000), elevated to
// P3 with the wall's nodes sent to the unit circle. After the first AL iteration the wall is
// 1e-6 away, and a multiplier update at the loose δ_k moved nothing: three AL iterations
// without a Newton step (7 in all) before δ went to δ* at once.
TEST(Morph, CurvesAThinBoundaryLayerToOrderThreeWithoutIdleIterations) {
  const Mesh linear = read_mesh(std::string(MESHMORPH_TEST_DATA) + "/bl_circle_coarse.msh");
  const Mesh mesh = elevate_order(linear, 3);
  const Topology topo = build_topology(mesh);
  BoundaryTargets bc;
  bc.role.assign(mesh.n_nodes(), NodeRole::Free);
  bc.target = mesh.x;
  bc.normal = Eigen::MatrixXd::Zero(2, static_cast<Eigen::Index>(mesh.n_nodes()));
  const std::vector<std::int32_t> wall = mesh.group_nodes(*mesh.find_group("wall"));
  for (std::int32_t node : mesh.group_nodes(*mesh.find_group("farfield"))) bc.role[node] = NodeRole::Fixed;
  for (std::int32_t node : wall) {
    bc.role[node] = NodeRole::Prescribed;
    bc.target.col(node) = mesh.x.col(node).normalized();
  }
  Eigen::MatrixXd x = mesh.x;
  const MorphResult r = Morpher(mesh, topo, bc, MorphOptions{}).solve(bc.target, x);
  ASSERT_TRUE(r.converged) << r.message;
  Mesh moved = mesh;
  moved.x = x;
  EXPECT_EQ(count_invalid_cells(moved), 0u);
  for (std::int32_t node : wall) EXPECT_NEAR(x.col(node).norm(), 1.0, 1e-8) << node;
  EXPECT_LE(r.outer, 4);
}

// Paper 001's Test 1: the unit square's boundary squeezed to 1% of its height (y ↦ 0.01 y).
// The distortion's barrier holds the thinnest cells against the penalty and the augmented
// Lagrangian stalls short of the boundary (DESIGN §6); the untangle pass from there places
// the boundary, untangles the cells that this inverts and ends valid with the boundary exact.
// Squeezes to 1% of the height, uniform and as a wedge (the left side at 1%, the right side
// kept): the optimum puts every cell at the squeeze's own aspect, q = 2f and about f. The
// weights grow ×β per update up to their bound and μ follows them; before it did, the
// uniform squeeze stalled 0.06 from its target, and before the exact Hessian's shift could
// fall below 1e-4 the wedge crawled at full steps to Newton's iteration limit.
TEST(Morph, ReachesSqueezesToOnePercentWithTheBestQualityTheyAllow) {
  const Mesh mesh = structured_mesh(ElementType::Triangle, 1, 10);
  const Topology topo = build_topology(mesh);
  for (const bool wedge : {false, true}) {
    Eigen::MatrixXd squeezed = mesh.x;
    const Eigen::ArrayXd factor = wedge ? (0.01 + 0.99 * mesh.x.row(0).array()).eval() : Eigen::ArrayXd::Constant(mesh.x.cols(), 0.01);
    squeezed.row(1) = (mesh.x.row(1).array() * factor.transpose()).matrix();
    const BoundaryTargets bc = all_boundary(mesh, topo, squeezed);
    MorphOptions o;
    o.finish_by_untangle = false;
    Eigen::MatrixXd x = mesh.x;
    const MorphResult r = Morpher(mesh, topo, bc, o).solve(bc.target, x);
    ASSERT_TRUE(r.converged) << (wedge ? "wedge: " : "uniform: ") << r.message;
    EXPECT_LE(r.history.back().boundary_error_max, 1e-9 * std::sqrt(2.0));
    EXPECT_GT(min_quality(mesh, x), wedge ? 0.0099 : 0.0199) << (wedge ? "wedge" : "uniform");
  }
}

TEST(Morph, AnUntanglePassFinishesASqueezeWhereTheAugmentedLagrangianStalls) {
  const Mesh mesh = structured_mesh(ElementType::Triangle, 1, 10);
  const Topology topo = build_topology(mesh);
  Eigen::MatrixXd squeezed = mesh.x;
  squeezed.row(1) *= 0.01;
  const BoundaryTargets bc = all_boundary(mesh, topo, squeezed);
  // The augmented Lagrangian reaches this squeeze by itself (Morph.ReachesSqueezes...); a
  // penalty that starts 1e16 times too soft makes it stall: six penalty rises later it is
  // still a quarter of the height away.
  MorphOptions o;
  o.penalty0 = 1e-16;
  o.finish_by_untangle = false;
  Eigen::MatrixXd stalled = mesh.x;
  const MorphResult alone = Morpher(mesh, topo, bc, o).solve(bc.target, stalled);
  ASSERT_FALSE(alone.converged);
  EXPECT_NE(alone.message.find("stalled"), std::string::npos) << alone.message;
  EXPECT_FALSE(alone.finish.has_value());

  Eigen::MatrixXd x = mesh.x;
  o.finish_by_untangle = true;
  const MorphResult r = Morpher(mesh, topo, bc, o).solve(bc.target, x);
  ASSERT_TRUE(r.converged) << r.message;
  ASSERT_TRUE(r.finish.has_value());
  EXPECT_TRUE(r.finish->valid);
  EXPECT_GT(r.finish->boundary_error_max, 1e-3);  // where the augmented Lagrangian stopped
  EXPECT_GT(r.finish->initial_inverted, 0u);      // placing the boundary from there tangled it
  EXPECT_NE(r.message.find("untangle pass"), std::string::npos) << r.message;
  Mesh moved = mesh;
  moved.x = x;
  EXPECT_EQ(count_invalid_cells(moved), 0u);
  for (std::size_t i = 0; i < mesh.n_nodes(); ++i) {
    const auto j = static_cast<Eigen::Index>(i);
    if (bc.role[i] == NodeRole::Prescribed) {
      EXPECT_EQ(x.col(j), squeezed.col(j));
    }
  }
  EXPECT_GT(min_quality(mesh, x), 0.005);

  // A series goes on from there, back to half the height: the augmented Lagrangian starts
  // afresh (μ₀ of the state it starts from, not the ≥ 1e12 μ₀ that stalled) and needs no
  // other pass.
  Eigen::MatrixXd half = mesh.x;
  half.row(1) *= 0.5;
  Morpher series(mesh, topo, bc, o);
  Eigen::MatrixXd y = mesh.x;
  const MorphResult r1 = series.solve(bc.target, y, 1);
  ASSERT_TRUE(r1.finish.has_value());
  const BoundaryTargets back = all_boundary(mesh, topo, half);
  const MorphResult r2 = series.solve(back.target, y, 2);
  EXPECT_TRUE(r2.converged) << r2.message;
  EXPECT_FALSE(r2.finish.has_value());
  EXPECT_LT(r2.history.front().mu, 1e-6 * r1.history.back().mu);
}

// Cells with no free node are what the motion makes them: one it inverts stops the run
// before any iteration, naming the cause (rather than stalling after six penalty rises).
TEST(Morph, StopsAtOnceWhenTheMotionInvertsACellWithNoFreeNode) {
  const Mesh mesh = structured_mesh(ElementType::Triangle, 1, 3);
  const Topology topo = build_topology(mesh);
  Eigen::MatrixXd mirrored = mesh.x;
  mirrored.row(0) = (1.0 - mesh.x.row(0).array()).matrix();  // x ↦ 1 − x turns every cell over
  const BoundaryTargets bc = all_boundary(mesh, topo, mirrored);
  Eigen::MatrixXd x = mesh.x;
  const MorphResult r = Morpher(mesh, topo, bc, MorphOptions{}).solve(bc.target, x);
  EXPECT_FALSE(r.converged);
  EXPECT_TRUE(r.history.empty());
  EXPECT_NE(r.message.find(" cells have only fixed and prescribed nodes and the motion inverts them"), std::string::npos) << r.message;
  EXPECT_EQ(x, mesh.x);
}

TEST(Morph, RejectsAnInvertedInputMesh) {
  Mesh mesh = structured_mesh(ElementType::Triangle, 1, 2);
  mesh.x.col(4) = Eigen::Vector2d(1.4, 1.4);  // the centre node beyond the top-right corner
  const Topology topo = build_topology(mesh);
  const BoundaryTargets bc = all_boundary(mesh, topo, mesh.x);
  EXPECT_THROW(Morpher(mesh, topo, bc, MorphOptions{}), InputError);
}

// PETSc's multigrids as the Newton steps' linear solver: a twist of a cube's boundary (34° at
// the top) ends converged and valid with the augmented-Lagrangian and Newton counts of
// CHOLMOD's run (CG's solutions end Newton at the decrement, not at an exact step).
TEST(Morph, PetscSolversMorphATwistedCubeLikeCholmod) {
  const Mesh mesh = structured_mesh(ElementType::Tetrahedron, 1, 8);
  const Topology topo = build_topology(mesh);
  Eigen::MatrixXd twisted = mesh.x;
  for (Eigen::Index j = 0; j < twisted.cols(); ++j) {
    const Eigen::Vector3d p = mesh.x.col(j);
    twisted.col(j) = Eigen::AngleAxisd(0.6 * p.z(), Eigen::Vector3d::UnitZ()) * (p - Eigen::Vector3d(0.5, 0.5, 0.0)) +
                     Eigen::Vector3d(0.5, 0.5, 0.0);
  }
  const BoundaryTargets bc = all_boundary(mesh, topo, twisted);
  const LinearSolverKind kinds[3] = {LinearSolverKind::Cholesky, LinearSolverKind::PetscGamg, LinearSolverKind::PetscHypre};
  MorphResult results[3];
  double quality[3];
  for (int k = 0; k < 3; ++k) {
    SCOPED_TRACE(k);
    MorphOptions o;
    o.solver = kinds[k];
    Eigen::MatrixXd x = mesh.x;
    results[k] = Morpher(mesh, topo, bc, o).solve(bc.target, x);
    ASSERT_TRUE(results[k].converged) << results[k].message;
    quality[k] = min_quality(mesh, x);
    for (std::int32_t node : boundary_nodes(mesh, topo)) EXPECT_LT((x.col(node) - twisted.col(node)).norm(), 1e-6);
  }
  EXPECT_GT(quality[0], 0.9);
  for (int k = 1; k < 3; ++k) {
    SCOPED_TRACE(k);
    EXPECT_NEAR(quality[k], quality[0], 1e-4);
    EXPECT_LE(results[k].outer, results[0].outer + 4);  // 9 with CHOLMOD, 12 and 10 with GAMG and BoomerAMG
    EXPECT_LE(results[k].newton, 2 * results[0].newton);
    EXPECT_GT(results[k].krylov, 0);
  }
}

}  // namespace
}  // namespace meshmorph
