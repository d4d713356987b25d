// SPDX-License-Identifier: MIT
#include "meshmorph/methods/untangle.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <random>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "meshmorph/error.h"
#include "meshmorph/fem/jacobian.h"
#include "meshmorph/fem/structured.h"
#include "meshmorph/fem/trace.h"
#include "meshmorph/fem/validity.h"
#include "meshmorph/io/mesh_io.h"
#include "methods/detail/untangle_problem.h"

namespace meshmorph {
namespace {

using Motion = std::function<Eigen::VectorXd(const Eigen::VectorXd&)>;

// Boundary nodes where `moves` holds are Prescribed to motion(x), the other boundary nodes Fixed.
BoundaryTargets boundary(const Mesh& mesh, const Topology& topo, const std::function<bool(const Eigen::VectorXd&)>& moves,
                         const Motion& motion) {
  BoundaryTargets bc;
  bc.role.assign(mesh.n_nodes(), NodeRole::Free);
  bc.target = mesh.x;
  bc.normal = Eigen::MatrixXd::Zero(mesh.dim, static_cast<Eigen::Index>(mesh.n_nodes()));
  for (std::int32_t node : boundary_nodes(mesh, topo)) {
    const Eigen::VectorXd x = mesh.x.col(node);
    if (moves(x)) {
      bc.role[node] = NodeRole::Prescribed;
      bc.target.col(node) = motion(x);
    } else {
      bc.role[node] = NodeRole::Fixed;
    }
  }
  return bc;
}

BoundaryTargets fixed_boundary(const Mesh& mesh, const Topology& topo) {
  return boundary(mesh, topo, [](const Eigen::VectorXd&) { return false; }, nullptr);
}

// The top side (y = 1, or z = 1 in 3D) pushed down by `depth`·sin(πx)(·sin(πy)): with depth
// above the cell size the first row of cells under it inverts.
BoundaryTargets pushed_top(const Mesh& mesh, const Topology& topo, double depth) {
  const int d = mesh.dim;
  return boundary(
      mesh, topo, [d](const Eigen::VectorXd& x) { return std::abs(x(d - 1) - 1.0) < 1e-12; },
      [d, depth](const Eigen::VectorXd& x) {
        Eigen::VectorXd y = x;
        double bump = std::sin(M_PI * x(0));
        if (d == 3) bump *= std::sin(M_PI * x(1));
        y(d - 1) -= depth * bump;
        return y;
      });
}

// Interior nodes moved at random by up to `amount` of the spacing 1/n, the mesh staying valid.
Mesh perturbed(Mesh mesh, int n, double amount) {
  const Topology topo = build_topology(mesh);
  std::vector<bool> on_boundary(mesh.n_nodes(), false);
  for (std::int32_t node : boundary_nodes(mesh, topo)) on_boundary[node] = true;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-amount / n, amount / n);
  for (std::size_t i = 0; i < mesh.n_nodes(); ++i)
    if (!on_boundary[i])
      for (int k = 0; k < mesh.dim; ++k) mesh.x(k, static_cast<Eigen::Index>(i)) += u(rng);
  return mesh;
}

// The untangled positions x make `mesh` valid, at a positive quality, with every boundary node
// exactly on its target.
void expect_valid_on_targets(const Mesh& mesh, const BoundaryTargets& bc, const UntangleResult& r, const Eigen::MatrixXd& x) {
  Mesh moved = mesh;
  moved.x = x;
  EXPECT_EQ(count_invalid_cells(moved), 0u);
  EXPECT_GT(r.min_quality, 0.0);
  for (std::size_t i = 0; i < mesh.n_nodes(); ++i)
    if (bc.role[i] != NodeRole::Free) {
      EXPECT_EQ(x.col(static_cast<Eigen::Index>(i)), bc.target.col(static_cast<Eigen::Index>(i)));
    }
}

struct Case {
  ElementType type;
  int order;
  int n;
};

std::string case_name(const ::testing::TestParamInfo<Case>& info) {
  return std::string(name_of(info.param.type)) + "P" + std::to_string(info.param.order);
}

const Case kCases[] = {{ElementType::Triangle, 1, 6},      {ElementType::Quadrilateral, 1, 6},
                       {ElementType::Tetrahedron, 1, 3},   {ElementType::Hexahedron, 1, 3},
                       {ElementType::Triangle, 2, 4},      {ElementType::Tetrahedron, 2, 2}};

class UntangleCases : public ::testing::TestWithParam<Case> {};

// With the input as reference, a valid input is a minimiser of F: nothing moves.
TEST_P(UntangleCases, AValidInputIsAFixedPointOfTheInputReference) {
  const Case c = GetParam();
  const Mesh mesh = perturbed(structured_mesh(c.type, c.order, c.n), c.n * c.order * 2, 0.2);
  ASSERT_EQ(count_invalid_cells(mesh), 0u);
  const Topology topo = build_topology(mesh);
  const BoundaryTargets bc = fixed_boundary(mesh, topo);
  UntangleOptions o;
  o.solver = LinearSolverKind::Cholesky;
  Untangler untangler(mesh, topo, bc, o);
  Eigen::MatrixXd x = mesh.x;
  const UntangleResult r = untangler.solve(mesh.x, x);
  ASSERT_TRUE(r.converged) << r.message;
  EXPECT_EQ(r.initial_inverted, 0u);
  EXPECT_LE((x - mesh.x).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_NEAR(r.min_quality, 1.0, 1e-12);
}

// The top side pushed down by 90 % (more than a cell) tangles the mesh; untangle recovers a
// valid mesh with the boundary exactly at its targets, with either δ rule.
TEST_P(UntangleCases, RecoversAValidMeshFromATangledOne) {
  const Case c = GetParam();
  const Mesh mesh = structured_mesh(c.type, c.order, c.n);
  const Topology topo = build_topology(mesh);
  const BoundaryTargets bc = pushed_top(mesh, topo, 0.9);
  for (DeltaRule rule : {DeltaRule::Continuation, DeltaRule::Paper}) {
    UntangleOptions o;
    o.solver = LinearSolverKind::Cholesky;
    o.delta_rule = rule;
    o.predictor = false;
    Untangler untangler(mesh, topo, bc, o);
    Eigen::MatrixXd x = mesh.x;
    const UntangleResult r = untangler.solve(bc.target, x);
    EXPECT_GT(r.initial_inverted, 0u) << "the case must start tangled";
    ASSERT_TRUE(r.converged) << r.message;
    expect_valid_on_targets(mesh, bc, r, x);
    EXPECT_GT(r.history.size(), 1u);
    EXPECT_EQ(r.history.back().inverted, 0u);
    EXPECT_EQ(r.history.back().delta, 0.0) << "the last steps minimise the unregularized functional";
  }
}

INSTANTIATE_TEST_SUITE_P(Untangle, UntangleCases, ::testing::ValuesIn(kCases), case_name);

// Six equilateral triangles around a free centre: the regular reference's minimiser.
TEST(Untangle, AnEquilateralPatchIsAFixedPointOfTheRegularReference) {
  Mesh mesh;
  mesh.dim = 2;
  mesh.x.resize(2, 7);
  mesh.x.col(0) << 0.0, 0.0;
  for (int k = 0; k < 6; ++k) mesh.x.col(k + 1) << std::cos(k * M_PI / 3), std::sin(k * M_PI / 3);
  CellBlock block;
  block.type = ElementType::Triangle;
  block.order = 1;
  for (int k = 0; k < 6; ++k) block.nodes.insert(block.nodes.end(), {0, k + 1, (k + 1) % 6 + 1});
  mesh.cells.push_back(block);
  const Topology topo = build_topology(mesh);
  const BoundaryTargets bc = fixed_boundary(mesh, topo);
  UntangleOptions o;
  o.reference = UntangleReference::Regular;
  Untangler untangler(mesh, topo, bc, o);
  Eigen::MatrixXd x = mesh.x;
  x.col(0) << 0.3, -0.2;  // the centre off its place: smoothing brings it back
  const UntangleResult r = untangler.solve(mesh.x, x);
  ASSERT_TRUE(r.converged) << r.message;
  EXPECT_LE(x.col(0).norm(), 1e-3) << "eps_q stops once q_min changes by < 1%";
  Eigen::MatrixXd y = mesh.x;
  ASSERT_TRUE(untangler.solve(mesh.x, y).converged);
  EXPECT_LE((y - mesh.x).cwiseAbs().maxCoeff(), 1e-12);
}

// Paper 001 §2.1: a mesh graded 1 : 3.5 across keeps its grading when smoothed against itself
// (the reference-element form); against the regular triangle the grading relaxes away.
TEST(Untangle, TheInputReferenceKeepsTheGrading) {
  Mesh mesh = structured_mesh(ElementType::Triangle, 1, 8);
  const double k = std::log(3.5);
  for (Eigen::Index i = 0; i < mesh.x.cols(); ++i) mesh.x(0, i) = std::expm1(k * mesh.x(0, i)) / std::expm1(k);
  const Topology topo = build_topology(mesh);
  const BoundaryTargets bc = fixed_boundary(mesh, topo);
  // Mean area of the cells in the first and in the last column.
  const auto grading = [&](const Eigen::MatrixXd& x) {
    double left = 0.0, right = 0.0;
    const CellBlock& block = mesh.cells[0];
    for (std::size_t c = 0; c < block.n_cells(); ++c) {
      const std::int32_t* v = block.cell(c);
      const Eigen::Vector2d a = x.col(v[0]), b = x.col(v[1]), e = x.col(v[2]);
      const double area = 0.5 * std::abs((b - a)(0) * (e - a)(1) - (b - a)(1) * (e - a)(0));
      const double cx = (mesh.x(0, v[0]) + mesh.x(0, v[1]) + mesh.x(0, v[2])) / 3.0;
      if (cx < mesh.x.row(0).maxCoeff() * 0.05) left += area;
      if (cx > 0.85) right += area;
    }
    return right / left;
  };
  const double before = grading(mesh.x);
  ASSERT_GT(before, 2.5);
  for (UntangleReference ref : {UntangleReference::Input, UntangleReference::Regular}) {
    UntangleOptions o;
    o.reference = ref;
    Untangler untangler(mesh, topo, bc, o);
    Eigen::MatrixXd x = mesh.x;
    ASSERT_TRUE(untangler.solve(mesh.x, x).converged);
    const double change = std::abs(grading(x) / before - 1.0);
    if (ref == UntangleReference::Input) EXPECT_LT(change, 0.05);
    else EXPECT_GT(change, 0.05) << "the control: the regular reference relaxes the grading";
  }
}

// More steps of a time series with the differential predictor need fewer Newton steps than
// without (paper 001 Table I), and both end valid.
TEST(Untangle, ThePredictorSavesNewtonStepsOverATimeSeries) {
  const Mesh mesh = structured_mesh(ElementType::Triangle, 1, 8);
  const Topology topo = build_topology(mesh);
  const BoundaryTargets bc = pushed_top(mesh, topo, 0.9);
  long long newton[2] = {0, 0};
  for (int predictor = 0; predictor < 2; ++predictor) {
    UntangleOptions o;
    o.predictor = predictor == 1;
    Untangler untangler(mesh, topo, bc, o);
    Eigen::MatrixXd x = mesh.x;
    const int steps = 8;
    for (int s = 1; s <= steps; ++s) {
      const Eigen::MatrixXd target = mesh.x + (bc.target - mesh.x) * (static_cast<double>(s) / steps);
      const UntangleResult r = untangler.solve(target, x, s);
      ASSERT_TRUE(r.converged) << "step " << s << ": " << r.message;
      newton[predictor] += r.newton;
    }
  }
  EXPECT_LT(newton[1], newton[0]);
}

// The boundary pushed through the opposite side: no valid mesh exists. The run ends with a
// reason, in a bounded number of steps; a cell whose nodes are all on the boundary and that
// the motion inverts is reported at once.
TEST(Untangle, GivesUpWhenTheBoundaryFoldsOverItself) {
  const Mesh mesh = structured_mesh(ElementType::Triangle, 1, 4);
  const Topology topo = build_topology(mesh);
  const BoundaryTargets through = pushed_top(mesh, topo, 1.6);
  UntangleOptions o;
  o.max_newton = 60;
  Untangler untangler(mesh, topo, through, o);
  Eigen::MatrixXd x = mesh.x;
  const UntangleResult r = untangler.solve(through.target, x);
  EXPECT_FALSE(r.converged);
  EXPECT_FALSE(r.message.empty());
  EXPECT_LE(r.newton, 60);

  const Mesh two = structured_mesh(ElementType::Triangle, 1, 1);  // every node on the boundary
  const Topology topo2 = build_topology(two);
  const BoundaryTargets flip = boundary(
      two, topo2, [](const Eigen::VectorXd& p) { return p(0) > 0.5 && p(1) > 0.5; },
      [](const Eigen::VectorXd&) { return Eigen::Vector2d(-0.5, -0.5); });
  Untangler stuck(two, topo2, flip, UntangleOptions{});
  Eigen::MatrixXd y = two.x;
  const UntangleResult s = stuck.solve(flip.target, y);
  EXPECT_FALSE(s.converged);
  EXPECT_NE(s.message.find("no interior motion"), std::string::npos) << s.message;
  EXPECT_EQ(s.newton, 0);
}

// A cube of P3 tetrahedra whose inner nodes are moved at random (a seeded sweep) until a cell
// folds between its validity samples, every sample positive: the functional's points see no
// inverted cell, the Bernstein bounds do. Untangling with the box fixed and `certify` ends
// valid by the bounds and says so.
TEST(Untangle, AP3CellFoldedBetweenItsSamplesEndsValidByTheBernsteinBounds) {
  const Mesh cube = structured_mesh(ElementType::Tetrahedron, 3, 1);
  const Topology topo = build_topology(cube);
  const BoundaryTargets bc = fixed_boundary(cube, topo);
  const std::vector<std::uint8_t> keep(static_cast<std::size_t>(validity_samples(ElementType::Tetrahedron, 3).n_points()), 0);
  std::mt19937 random(5);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  Mesh folded = cube;
  bool found = false;
  for (int trial = 0; trial < 2000 && !found; ++trial) {
    folded.x = cube.x;
    for (std::size_t i = 0; i < cube.n_nodes(); ++i)
      if (bc.role[i] == NodeRole::Free)
        for (int k = 0; k < 3; ++k) folded.x(k, static_cast<Eigen::Index>(i)) += 0.12 * unit(random);
    const CellBlock& b = folded.cells[0];
    bool samples_valid = true;
    std::size_t bernstein_invalid = 0;
    for (std::size_t c = 0; c < b.n_cells(); ++c) {
      const Eigen::MatrixXd X = cell_coordinates(folded, b, c);
      samples_valid = samples_valid && min_jacobian_det(b.type, b.order, X, keep) > 0.0;
      bernstein_invalid += min_jacobian_det(b.type, b.order, X) > 0.0 ? 0 : 1;
    }
    found = samples_valid && bernstein_invalid > 0;
  }
  ASSERT_TRUE(found) << "no fold between the samples: the sweep does not test the bounds";
  UntangleOptions o;
  o.reference = UntangleReference::InputWhereValid;
  o.certify = true;
  Untangler untangler(folded, topo, bc, o);
  Eigen::MatrixXd x = folded.x;
  const UntangleResult r = untangler.solve(folded.x, x);
  EXPECT_EQ(r.initial_inverted, 0u);  // at the functional's points
  EXPECT_TRUE(r.converged) << r.message;
  EXPECT_NE(r.message.find("valid by the Bernstein bounds"), std::string::npos) << r.message;
  Mesh out = folded;
  out.x = x;
  EXPECT_EQ(count_invalid_cells(out), 0u);
}

TEST(Untangle, AnInputReferenceNeedsAValidInput) {
  Mesh mesh = structured_mesh(ElementType::Triangle, 1, 3);
  mesh.x.col(5) << 2.0, 2.0;  // an interior node thrown out of its cells
  const Topology topo = build_topology(mesh);
  const BoundaryTargets bc = fixed_boundary(mesh, topo);
  EXPECT_THROW(Untangler(mesh, topo, bc, UntangleOptions{}), InputError);
  UntangleOptions o;
  o.reference = UntangleReference::Regular;
  Untangler untangler(mesh, topo, bc, o);
  Eigen::MatrixXd x = mesh.x;
  const UntangleResult r = untangler.solve(mesh.x, x);
  EXPECT_GT(r.initial_inverted, 0u);
  EXPECT_TRUE(r.converged) << r.message;
}

// A slide plane at an angle to every axis: the mesh rotated off them, its top pushed down
// through the first row of cells, the inner nodes of its bottom sliding on the rotated plane
// (the rest of the boundary fixed). The predictor and every Newton step keep them on it while
// they move along it, and the mesh comes out valid.
TEST(Untangle, SlideNodesStayOnAnObliquePlane) {
  for (const Case c : {Case{ElementType::Triangle, 1, 4}, Case{ElementType::Tetrahedron, 1, 3}}) {
    Mesh mesh = structured_mesh(c.type, c.order, c.n);
    const int d = mesh.dim;
    const Topology topo = build_topology(mesh);
    BoundaryTargets bc = pushed_top(mesh, topo, 0.9);
    for (std::size_t i = 0; i < mesh.n_nodes(); ++i) {
      const Eigen::VectorXd x = mesh.x.col(static_cast<Eigen::Index>(i));
      bool inner_bottom = bc.role[i] == NodeRole::Fixed && std::abs(x(d - 1)) < 1e-12;
      for (int k = 0; k < d - 1; ++k) inner_bottom = inner_bottom && x(k) > 1e-12 && x(k) < 1.0 - 1e-12;
      if (!inner_bottom) continue;
      bc.role[i] = NodeRole::Slide;
      bc.normal(d - 1, static_cast<Eigen::Index>(i)) = -1.0;
    }
    const Eigen::MatrixXd R = d == 2 ? Eigen::MatrixXd(Eigen::Rotation2Dd(0.5).toRotationMatrix())
                                     : Eigen::MatrixXd(Eigen::AngleAxisd(0.5, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix());
    mesh.x = R * mesh.x;
    bc.target = R * bc.target;
    bc.normal = R * bc.normal;
    Eigen::MatrixXd x = mesh.x;
    const UntangleResult r = Untangler(mesh, topo, bc, UntangleOptions{}).solve(bc.target, x);
    ASSERT_TRUE(r.converged) << r.message;
    EXPECT_GT(r.initial_inverted, 0u) << "the case must start tangled";
    mesh.x = x;
    EXPECT_EQ(count_invalid_cells(mesh), 0u);
    double slid = 0.0;
    for (std::size_t i = 0; i < mesh.n_nodes(); ++i) {
      if (bc.role[i] != NodeRole::Slide) continue;
      const auto j = static_cast<Eigen::Index>(i);
      EXPECT_LE(std::abs(bc.normal.col(j).dot(x.col(j) - bc.target.col(j))), 1e-12) << "node " << i;
      slid = std::max(slid, (x.col(j) - bc.target.col(j)).norm());
    }
    EXPECT_GT(slid, 1e-3) << "the slide nodes move along their plane";
  }
}

// Eq. 13 at a tangled state: Δδ = −(F_δ + F_δx·dx)/F_δδ against differences of F in δ and x.
TEST(UntangleProblem, DeltaIncrementMatchesDifferencesOfTheEnergy) {
  const Mesh mesh = structured_mesh(ElementType::Triangle, 2, 3);
  const Topology topo = build_topology(mesh);
  const BoundaryTargets bc = pushed_top(mesh, topo, 0.8);
  UntangleProblem<2> P(mesh, topo, bc, UntangleReference::Input, -1.0, 1);
  Eigen::MatrixXd x = mesh.x;
  for (std::size_t i = 0; i < mesh.n_nodes(); ++i)
    if (bc.role[i] == NodeRole::Prescribed) {
      x.col(static_cast<Eigen::Index>(i)) = bc.target.col(static_cast<Eigen::Index>(i));
    }
  P.set_state(x);
  ASSERT_GT(P.measure().inverted, 0u);
  const double delta = 0.05;
  std::mt19937 rng(5);
  std::normal_distribution<double> normal(0.0, 0.01);
  Eigen::VectorXd dx(static_cast<Eigen::Index>(P.n_free()));
  for (Eigen::Index i = 0; i < dx.size(); ++i) dx[i] = normal(rng);
  // F(δ, x + t dx) by differences: F_δ, F_δδ, and ∂/∂t of F_δ.
  const auto F = [&](double dl, double t) {
    UntangleProblem<2> Q(mesh, topo, bc, UntangleReference::Input, -1.0, 1);
    Q.set_state(x);
    Q.set_delta(dl);
    return Q.trial_value(dx, t);
  };
  const double h = 1e-4 * delta, t = 1e-4;
  const auto F_d = [&](double s) { return (F(delta + h, s) - F(delta - h, s)) / (2 * h); };
  const double F_dd = (F(delta + h, 0) - 2 * F(delta, 0) + F(delta - h, 0)) / (h * h);
  const double F_dx = (F_d(t) - F_d(-t)) / (2 * t);
  P.set_delta(delta);
  EXPECT_NEAR(P.delta_increment(Eigen::VectorXd()), -F_d(0) / F_dd, 1e-5 * std::abs(F_d(0) / F_dd));
  EXPECT_NEAR(P.delta_increment(dx), -(F_d(0) + F_dx) / F_dd, 1e-5 * std::abs((F_d(0) + F_dx) / F_dd));
}

// At a minimiser of the input reference (the input itself), a scaling of the boundary has a
// scaled interior as minimiser all along its path (∂F/∂T = 0 at T = cI, whatever the cell
// sizes): the predictor's first-order step is exact. (A general affine motion is not: F sums
// the cells without volume weights, paper 001 eq. 1.)
TEST(UntangleProblem, ThePredictorIsExactForAnAffineMotionOfTheBoundary) {
  const Mesh mesh = perturbed(structured_mesh(ElementType::Tetrahedron, 1, 3), 3, 0.2);
  const Topology topo = build_topology(mesh);
  const Motion affine = [](const Eigen::VectorXd& p) { return Eigen::VectorXd(1.7 * p + Eigen::Vector3d(0.5, 0, -1)); };
  const BoundaryTargets bc = boundary(mesh, topo, [](const Eigen::VectorXd&) { return true; }, affine);
  UntangleProblem<3> P(mesh, topo, bc, UntangleReference::Input, -1.0, 1);
  LinearSolverOptions lo;
  lo.kind = LinearSolverKind::Cholesky;
  lo.block_size = 3;
  auto solver = make_linear_solver(lo, P.n_free());
  Eigen::MatrixXd increment;
  ASSERT_TRUE(P.predict(bc.target, *solver, increment));
  for (std::size_t i = 0; i < mesh.n_nodes(); ++i)
    if (bc.role[i] == NodeRole::Free) {
      const Eigen::Index col = static_cast<Eigen::Index>(i);
      EXPECT_LE((mesh.x.col(col) + increment.col(col) - affine(mesh.x.col(col))).norm(), 1e-10);
    }
}

// The hybrid layer mesh (prisms and hexahedra under tetrahedra, pyramids between;
// tests/data/hybrid_layer.geo): its bottom raised by a bump of 0.105 at its highest node, more
// than the 0.1 of the layer, tangles prisms and tetrahedra; untangle recovers a valid mesh
// with the bottom on its targets.
TEST(Untangle, RecoversAHybridLayerMesh) {
  const Mesh mesh = read_mesh(std::string(MESHMORPH_TEST_DATA) + "/hybrid_layer.msh");
  const Topology topo = build_topology(mesh);
  const BoundaryTargets bc = boundary(
      mesh, topo, [](const Eigen::VectorXd& x) { return std::abs(x(2)) < 1e-12; },
      [](const Eigen::VectorXd& x) {
        Eigen::VectorXd y = x;
        y(2) += 0.5 * std::exp(-((x(0) - 0.5) * (x(0) - 0.5) + (x(1) - 0.5) * (x(1) - 0.5)) / 0.02);
        return y;
      });
  Mesh tangled = mesh;
  for (std::size_t i = 0; i < mesh.n_nodes(); ++i)
    if (bc.role[i] == NodeRole::Prescribed) tangled.x.col(static_cast<Eigen::Index>(i)) = bc.target.col(static_cast<Eigen::Index>(i));
  std::size_t inverted_prisms = 0;
  for (const CellBlock& b : tangled.cells)
    if (b.type == ElementType::Prism)
      for (std::size_t c = 0; c < b.n_cells(); ++c)
        inverted_prisms += min_jacobian_det(b.type, b.order, cell_coordinates(tangled, b, c)) <= 0.0;
  ASSERT_GT(inverted_prisms, 0u) << "the case must tangle the layer";
  UntangleOptions o;
  o.solver = LinearSolverKind::Cholesky;
  Untangler untangler(mesh, topo, bc, o);
  Eigen::MatrixXd x = mesh.x;
  const UntangleResult r = untangler.solve(bc.target, x);
  EXPECT_GE(r.initial_inverted, inverted_prisms);
  ASSERT_TRUE(r.converged) << r.message;
  expect_valid_on_targets(mesh, bc, r, x);
}

// A P2 square whose corner triangle (all three corners on the boundary) is folded by its one
// interior node pulled past the square's corner.
struct FoldedCorner {
  Mesh mesh = structured_mesh(ElementType::Triangle, 2, 4);
  Topology topology;
  Eigen::Vector2d corner;
  FoldedCorner() {
    topology = build_topology(mesh);
    std::vector<std::uint8_t> on_boundary(mesh.n_nodes(), 0);
    for (std::int32_t node : boundary_nodes(mesh, topology)) on_boundary[static_cast<std::size_t>(node)] = 1;
    const CellBlock& block = mesh.cells[0];
    for (std::size_t c = 0; c < block.n_cells(); ++c) {
      const std::int32_t* n = block.cell(c);
      if (!(on_boundary[n[0]] && on_boundary[n[1]] && on_boundary[n[2]])) continue;
      // The corner of the square is the cell's corner with two boundary edges; the midnode
      // opposite it (local 4: edge 1–2 for corner 0, Gmsh order 3: 0–1, 4: 1–2, 5: 2–0) is interior.
      for (int a = 0; a < 3; ++a) {
        const int mid = 3 + (a + 1) % 3;
        if (on_boundary[n[mid]]) continue;
        corner = mesh.x.col(n[a]);
        mesh.x.col(n[mid]) = corner - 0.2 * (Eigen::Vector2d(mesh.x.col(n[mid])) - corner);
        return;
      }
    }
  }
};

TEST(Untangle, ACellFoldedAgainstTheBoundaryIsRepairedInAPatchWithTheBoundarySliding) {
  const FoldedCorner f;
  const std::size_t n = f.mesh.n_nodes();
  ASSERT_GT(count_invalid_cells(f.mesh), 0u);
  const BoundaryTargets bc = boundary(f.mesh, f.topology, [](const Eigen::VectorXd&) { return false; }, {});
  EXPECT_EQ(boundary_bound_inverted(f.mesh, bc), 1u);

  // Every side node slides on its side; the square's four corners are in no surface.
  std::vector<std::uint8_t> may_slide(n, 0);
  for (std::int32_t node : boundary_nodes(f.mesh, f.topology)) may_slide[static_cast<std::size_t>(node)] = 1;
  const std::vector<FitTerm> surfaces = untangle_surfaces(f.mesh, f.topology, f.topology.boundary_facets, may_slide, 30.0);
  std::vector<int> terms_of(n, 0);
  for (const FitTerm& t : surfaces)
    for (std::int32_t node : t.nodes) ++terms_of[static_cast<std::size_t>(node)];
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d x = f.mesh.x.col(static_cast<Eigen::Index>(i));
    const bool square_corner = (x.array() == 0.0 || x.array() == 1.0).all();
    EXPECT_EQ(terms_of[i], may_slide[i] && !square_corner ? 1 : 0) << "node " << i;
  }

  Eigen::MatrixXd x = f.mesh.x;
  const LocalUntangle local = untangle_locally(f.mesh, f.topology, may_slide, 30.0, 1, {}, x);
  EXPECT_TRUE(local.result.converged) << local.result.message;
  // The input's invalid cells given (as the untangle command passes them): the same repair.
  const std::vector<std::uint8_t> invalid = invalid_cells(f.mesh);
  EXPECT_EQ(boundary_bound_inverted(f.mesh, bc, &invalid), 1u);
  Eigen::MatrixXd given = f.mesh.x;
  const LocalUntangle again = untangle_locally(f.mesh, f.topology, may_slide, 30.0, 1, {}, given, &invalid);
  EXPECT_EQ(again.cells, local.cells);
  EXPECT_EQ(given, x);
  EXPECT_GT(local.cells, 1u);
  EXPECT_LT(local.cells, f.mesh.n_cells());
  Mesh repaired = f.mesh;
  repaired.x = x;
  EXPECT_EQ(count_invalid_cells(repaired), 0u);
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d p = x.col(static_cast<Eigen::Index>(i)), p0 = f.mesh.x.col(static_cast<Eigen::Index>(i));
    if (may_slide[i]) {
      EXPECT_LT(std::min({p.x(), 1.0 - p.x(), p.y(), 1.0 - p.y()}), 1e-12) << "node " << i << " left the boundary";
    }
    if ((p0 - f.corner).norm() > 0.8) {
      EXPECT_EQ(p, p0) << "node " << i << " outside the patch moved";
    }
  }
}

}  // namespace
}  // namespace meshmorph
