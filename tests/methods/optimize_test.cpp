// SPDX-License-Identifier: MIT
#include "meshmorph/methods/optimize.h"

#include <algorithm>
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "meshmorph/fem/elevate.h"
#include "meshmorph/fem/lagrange_basis.h"
#include "meshmorph/fem/structured.h"
#include "meshmorph/fem/trace.h"
#include "meshmorph/fem/validity.h"
#include "meshmorph/geometry/facet_surface.h"
#include "meshmorph/io/mesh_io.h"
#include "methods/detail/fit_problem.h"

namespace meshmorph {
namespace {

std::vector<std::uint8_t> fixed_boundary(const Mesh& mesh, const Topology& topo) {
  std::vector<std::uint8_t> fixed(static_cast<std::size_t>(mesh.dim) * mesh.n_nodes(), 0);
  for (std::int32_t node : boundary_nodes(mesh, topo)) std::fill_n(fixed.begin() + mesh.dim * node, mesh.dim, 1);
  return fixed;
}

// Moves the interior nodes at random by up to `amount` of the node spacing `h`.
Eigen::MatrixXd jitter_interior(const Mesh& mesh, const Topology& topo, double amount, double h, unsigned seed) {
  std::vector<std::uint8_t> boundary(mesh.n_nodes(), 0);
  for (std::int32_t node : boundary_nodes(mesh, topo)) boundary[static_cast<std::size_t>(node)] = 1;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-amount * h, amount * h);
  Eigen::MatrixXd x = mesh.x;
  for (Eigen::Index i = 0; i < x.cols(); ++i)
    if (!boundary[static_cast<std::size_t>(i)])
      for (Eigen::Index k = 0; k < x.rows(); ++k) x(k, i) += u(rng);
  return x;
}

// The ideal grid minimises μ (μ = 0 on every cell): optimize takes no step and moves nothing.
TEST(Optimize, AnOptimalMeshStaysPut) {
  for (ElementType type : {ElementType::Quadrilateral, ElementType::Hexahedron}) {
    const Mesh mesh = structured_mesh(type, 2, 3);
    const Topology topo = build_topology(mesh);
    Eigen::MatrixXd x = mesh.x;
    const OptimizeResult r = optimize_mesh(mesh, topo, fixed_boundary(mesh, topo), {}, {}, x);
    EXPECT_TRUE(r.converged) << r.message;
    EXPECT_EQ(r.newton, 0) << name_of(type);
    EXPECT_NEAR(r.energy, 0.0, 1e-12);
    EXPECT_NEAR(r.mu_max, 0.0, 1e-12);
    EXPECT_EQ((x - mesh.x).cwiseAbs().maxCoeff(), 0.0);
  }
}

// A jittered interior with the boundary fixed: Newton returns to the grid (the unique
// μ = 0 configuration), to the relative gradient tolerance, and stays valid throughout.
TEST(Optimize, AJitteredInteriorReturnsToTheGrid) {
  for (ElementType type : {ElementType::Quadrilateral, ElementType::Hexahedron}) {
    for (int order : {1, 2}) {
      SCOPED_TRACE(std::string(name_of(type)) + " order " + std::to_string(order));
      const int n = 4;
      Mesh mesh = structured_mesh(type, order, n);
      const Topology topo = build_topology(mesh);
      const Eigen::MatrixXd grid = mesh.x;
      mesh.x = jitter_interior(mesh, topo, 0.1, 1.0 / (n * order), 3);
      ASSERT_EQ(count_invalid_cells(mesh), 0u);
      Eigen::MatrixXd x = mesh.x;
      const OptimizeResult r = optimize_mesh(mesh, topo, fixed_boundary(mesh, topo), {}, {}, x);
      EXPECT_TRUE(r.converged) << r.message;
      EXPECT_GT(r.energy0, 1e-3);
      EXPECT_LT(r.energy, 1e-12);
      EXPECT_LT((x - grid).cwiseAbs().maxCoeff(), 1e-6);
      EXPECT_LE(r.newton, 20);
      for (std::size_t k = 1; k < r.history.size(); ++k) {
        EXPECT_LE(r.history[k].energy, r.history[k - 1].energy);
        EXPECT_GT(r.history[k].min_det, 0.0);
      }
    }
  }
}

// The hybrid layer mesh (hexahedra, prisms, pyramids, tetrahedra; tests/data/hybrid_layer.geo)
// with its interior jittered by a tenth of the layers' thickness: the energy drops, every
// iterate valid.
TEST(Optimize, AHybridLayerMeshImprovesAndStaysValid) {
  Mesh mesh = read_mesh(std::string(MESHMORPH_TEST_DATA) + "/hybrid_layer.msh");
  const Topology topo = build_topology(mesh);
  mesh.x = jitter_interior(mesh, topo, 0.1, 0.1 / 3, 5);
  ASSERT_EQ(count_invalid_cells(mesh), 0u);
  Eigen::MatrixXd x = mesh.x;
  const OptimizeResult r = optimize_mesh(mesh, topo, fixed_boundary(mesh, topo), {}, {}, x);
  EXPECT_TRUE(r.converged) << r.message;
  EXPECT_LT(r.energy, r.energy0);
  for (const auto& h : r.history) EXPECT_GT(h.min_det, 0.0);
  mesh.x = x;
  EXPECT_EQ(count_invalid_cells(mesh), 0u);
}

// Quartic prisms below quartic tetrahedra: the unit square × [0, ½] in two prisms and × [½, 1]
// in six Kuhn tetrahedra (their triangles meet the prisms' tops), raised to order 4. Neither
// is the regular cell: the energy drops, every iterate valid (the elements' derivatives are
// the registry's, tests/energy/element_energy_test.cpp).
TEST(Optimize, AQuarticMeshOfPrismsAndTetrahedraImprovesAndStaysValid) {
  const Mesh prisms = structured_mesh(ElementType::Prism, 1, 1), tets = structured_mesh(ElementType::Tetrahedron, 1, 1);
  Mesh mesh;
  mesh.dim = 3;
  std::vector<Eigen::Vector3d> points;
  const auto node = [&](Eigen::Vector3d p) {
    for (std::size_t j = 0; j < points.size(); ++j)
      if ((points[j] - p).norm() < 1e-12) return static_cast<std::int32_t>(j);
    points.push_back(p);
    return static_cast<std::int32_t>(points.size() - 1);
  };
  for (const auto& [part, z0] : {std::pair{&prisms, 0.0}, std::pair{&tets, 0.5}}) {
    CellBlock b{part->cells[0].type, 1, {}, {}, {}};
    for (std::size_t c = 0; c < part->cells[0].n_cells(); ++c) {
      std::vector<std::int32_t> v;
      for (int a = 0; a < part->cells[0].n_nodes_per_cell(); ++a) {
        const Eigen::Vector3d p = part->x.col(part->cells[0].cell(c)[a]);
        v.push_back(node({p(0), p(1), z0 + 0.5 * p(2)}));
      }
      b.push_back(v.data(), 1, 1);
    }
    mesh.cells.push_back(b);
  }
  mesh.x.resize(3, static_cast<Eigen::Index>(points.size()));
  for (std::size_t j = 0; j < points.size(); ++j) {
    mesh.x.col(static_cast<Eigen::Index>(j)) = points[j];
    mesh.node_tags.push_back(static_cast<std::int64_t>(j) + 1);
  }
  mesh = elevate_order(mesh, 4);
  const Topology topo = build_topology(mesh);
  ASSERT_EQ(boundary_nodes(mesh, topo).size(), mesh.n_nodes() - 3u * 3u * 7u);  // the 3 × 3 × 7 inner lattice
  Eigen::MatrixXd x = mesh.x;
  const OptimizeResult r = optimize_mesh(mesh, topo, fixed_boundary(mesh, topo), {}, {}, x);
  EXPECT_TRUE(r.converged) << r.message;
  EXPECT_LT(r.energy, r.energy0);
  for (std::size_t k = 1; k < r.history.size(); ++k) {
    EXPECT_LE(r.history[k].energy, r.history[k - 1].energy);
    EXPECT_GT(r.history[k].min_det, 0.0);
  }
  mesh.x = x;
  EXPECT_EQ(count_invalid_cells(mesh), 0u);
}

// A quarter annulus 1 ≤ r ≤ 2 (the unit square mapped by polar coordinates, so every node of
// "left" lies on the unit circle exactly); `grading` > 0 crowds the nodes towards the ends.
Mesh quarter_annulus(ElementType type, int order, int n, double grading = 0.0) {
  Mesh mesh = structured_mesh(type, order, n);
  for (Eigen::Index i = 0; i < mesh.x.cols(); ++i) {
    const double y = mesh.x(1, i), r = 1.0 + mesh.x(0, i), t = 0.5 * M_PI * (y + grading * std::sin(2.0 * M_PI * y));
    mesh.x.col(i) = Eigen::Vector2d(r * std::cos(t), r * std::sin(t));
  }
  return mesh;
}

LevelSetFunction unit_circle() {
  return LevelSetFunction(LevelSet{SphereLevelSet{Eigen::Vector2d::Zero(), 1.0}, "circle"}, 2);
}

// The constrained derivatives: along the tangent t of a slide node, with trial points
// projected back onto the circle, F' = gᵀt and F'' = tᵀHt (the Hessian holds the curvature
// term −λ∇²σ of the Lagrangian); the normal direction is decoupled (H n = c n, g·n = 0).
TEST(OptimizeSlide, DerivativesAlongTheCircleMatchDifferences) {
  const Mesh mesh = quarter_annulus(ElementType::Quadrilateral, 2, 3);
  const Topology topo = build_topology(mesh);
  std::vector<std::uint8_t> fixed = fixed_boundary(mesh, topo);
  std::vector<std::int32_t> left = mesh.group_nodes(*mesh.find_group("left"));
  std::vector<std::int32_t> inner;  // the circle's nodes except its two ends (corners)
  for (std::int32_t node : left)
    if (std::abs(mesh.x(0, node)) > 1e-12 && std::abs(mesh.x(1, node)) > 1e-12) inner.push_back(node);
  for (std::int32_t node : inner) std::fill_n(fixed.begin() + 2 * node, 2, 0);
  const std::vector<FitTerm> no_terms, slides{{unit_circle(), inner}};
  FitOptions o;
  FitProblem<2> P(mesh, topo, no_terms, fixed, o, mesh.x, slides);
  Assembly a;
  P.evaluate(HessianMode::Exact, a);
  DofMap dofs = DofMap::from_mask(2, fixed);
  const double h = 1e-5;
  for (std::int32_t node : inner) {
    const Eigen::Vector2d p = mesh.x.col(node);
    const Eigen::Vector2d t(-p[1], p[0]), nrm = p;
    Eigen::VectorXd e = Eigen::VectorXd::Zero(a.gradient.size());
    const std::int32_t i = dofs.first(static_cast<std::size_t>(node));
    e.segment<2>(i) = t;
    const double f0 = P.energy(), fp = P.trial_value(e, h), fm = P.trial_value(e, -h);
    const double d1 = (fp - fm) / (2 * h), d2 = (fp - 2 * f0 + fm) / (h * h);
    EXPECT_NEAR(a.gradient.dot(e), d1, 1e-7 * std::max(1.0, std::abs(d1))) << node;
    EXPECT_NEAR(e.dot(a.hessian * e), d2, 1e-4 * std::max(1.0, std::abs(d2))) << node;
    EXPECT_NEAR(a.gradient.segment<2>(i).dot(nrm), 0.0, 1e-12);
    Eigen::VectorXd en = Eigen::VectorXd::Zero(a.gradient.size());
    en.segment<2>(i) = nrm;
    const Eigen::VectorXd Hn = a.hessian * en;
    EXPECT_NEAR((Hn - en * en.dot(Hn)).norm(), 0.0, 1e-10 * Hn.norm()) << node;
  }
}

// Sliding on the circle: the nodes stay on it to rounding, and the energy ends below the
// fixed optimum's (a feasible sliding state). Curved cells only: linear
// ones meet the circle at their corners alone.
TEST(OptimizeSlide, NodesStayOnTheCircleAndTheEnergyDrops) {
  for (int order : {2, 3}) {
    SCOPED_TRACE("order " + std::to_string(order));
    const Mesh mesh = quarter_annulus(ElementType::Quadrilateral, order, 4);
    const Topology topo = build_topology(mesh);
    std::vector<std::uint8_t> fixed = fixed_boundary(mesh, topo);
    Eigen::MatrixXd x_fixed = mesh.x;
    const OptimizeResult rf = optimize_mesh(mesh, topo, fixed, {}, {}, x_fixed);
    std::vector<std::int32_t> inner;
    for (std::int32_t node : mesh.group_nodes(*mesh.find_group("left")))
      if (std::abs(mesh.x(0, node)) > 1e-12 && std::abs(mesh.x(1, node)) > 1e-12) inner.push_back(node);
    for (std::int32_t node : inner) std::fill_n(fixed.begin() + 2 * node, 2, 0);
    Eigen::MatrixXd x = mesh.x;
    const OptimizeResult r = optimize_mesh(mesh, topo, fixed, {{unit_circle(), inner}}, {}, x);
    EXPECT_TRUE(rf.converged) << rf.message;
    // Not required to converge: on P3 the sliding optimum lies in a shallow valley where
    // Newton creeps (linear rate ≈ 0.9), the energy still falling at max_newton.
    EXPECT_LT(r.energy, rf.energy);
    double off = 0.0, moved = 0.0;
    for (std::int32_t node : inner) {
      off = std::max(off, std::abs(x.col(node).norm() - 1.0));
      moved = std::max(moved, (x.col(node) - mesh.x.col(node)).norm());
    }
    EXPECT_LT(off, 1e-14);
    EXPECT_GT(moved, 1e-3);  // they did slide
    EXPECT_GT(r.min_det, 0.0);
  }
}

// Planes of a cube: faces slide, edges slide on their lines, the 8 corners are fixed; from a
// jittered state (interior and tangential boundary moves) Newton finds a μ = 0 grid again.
TEST(OptimizeSlide, PlanarBoundarySlidesOnTheCubesFacesAndEdges) {
  Mesh mesh = structured_mesh(ElementType::Hexahedron, 2, 3);
  const Topology topo = build_topology(mesh);
  std::vector<std::uint8_t> fixed(3 * mesh.n_nodes(), 0);
  const std::vector<FitTerm> slides = boundary_slides(mesh, topo, topo.boundary_facets, 30.0, true, fixed);
  EXPECT_EQ(slides.size(), 6u);
  std::size_t fixed_nodes = 0;
  for (std::size_t i = 0; i < mesh.n_nodes(); ++i) fixed_nodes += fixed[3 * i];
  EXPECT_EQ(fixed_nodes, 8u);
  // Tangential jitter: a node moves only along the coordinates in which it is not on a face.
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-0.03, 0.03);
  for (Eigen::Index i = 0; i < mesh.x.cols(); ++i)
    for (int k = 0; k < 3; ++k)
      if (const double v = mesh.x(k, i); v > 1e-12 && v < 1.0 - 1e-12) mesh.x(k, i) += u(rng);
  ASSERT_EQ(count_invalid_cells(mesh), 0u);
  Eigen::MatrixXd x = mesh.x;
  const OptimizeResult r = optimize_mesh(mesh, topo, fixed, slides, {}, x);
  EXPECT_TRUE(r.converged) << r.message;
  EXPECT_LT(r.energy, 1e-12);
  for (const FitTerm& t : slides)
    for (std::int32_t node : t.nodes) EXPECT_LT(std::abs(t.sigma.value(x.col(node))), 1e-14);
}

// `--boundary slide` on a quarter annulus of curved cells: both arcs slide on their own
// discrete curves (the input's P2/P3 edges, no level set given), the straight sides on their
// lines, and the 4 corners stay. The arcs' nodes end on the input's curves to rounding, so
// within the input's distance from the exact circles, and the energy ends below the fixed
// boundary's.
TEST(OptimizeSlide, CurvedBoundarySlidesOnTheInputsDiscreteCurves) {
  for (int order : {2, 3}) {
    SCOPED_TRACE("order " + std::to_string(order));
    // Graded at P2 (uniform cells leave the arcs in place by symmetry); uniform at P3, where
    // graded cells stall (docs/optimize.md, What is left).
    const Mesh mesh = quarter_annulus(ElementType::Quadrilateral, order, 4, order == 2 ? 0.1 : 0.0);
    const Topology topo = build_topology(mesh);
    std::vector<std::uint8_t> fixed(2 * mesh.n_nodes(), 0);
    const std::vector<FitTerm> slides = boundary_slides(mesh, topo, topo.boundary_facets, 30.0, true, fixed);
    EXPECT_EQ(slides.size(), 4u);
    std::size_t fixed_nodes = 0;
    for (std::size_t i = 0; i < mesh.n_nodes(); ++i) fixed_nodes += fixed[2 * i];
    EXPECT_EQ(fixed_nodes, 4u);
    // Planes only (`slide-planes`): the straight sides slide, every node of the arcs is fixed.
    std::vector<std::uint8_t> planar_fixed(2 * mesh.n_nodes(), 0);
    const std::vector<FitTerm> planar = boundary_slides(mesh, topo, topo.boundary_facets, 30.0, false, planar_fixed);
    EXPECT_EQ(planar.size(), 2u);
    std::size_t planar_free = 0;
    for (const FitTerm& t : planar) planar_free += t.nodes.size();
    EXPECT_EQ(planar_free + static_cast<std::size_t>(std::count(planar_fixed.begin(), planar_fixed.end(), 1)) / 2,
              boundary_nodes(mesh, topo).size());
    // The inner arc's facets, and how far the input's curve strays from the unit circle.
    std::vector<std::int32_t> arc;
    double input_error = 0.0;
    for (std::int32_t f : topo.boundary_facets) {
      const CellFacet cf = topo.facets[static_cast<std::size_t>(f)][0];
      const auto [blk, cell] = topo.locate(cf.cell);
      const std::vector<std::int32_t> nodes = facet_nodes(mesh.cells[blk], cell, cf.local);
      if (std::abs(mesh.x.col(nodes[0]).norm() - 1.0) > 1e-12 || std::abs(mesh.x.col(nodes[1]).norm() - 1.0) > 1e-12) continue;
      arc.push_back(f);
      const LagrangeBasis& basis = lagrange_basis(ElementType::Line, order);
      for (int i = 0; i <= 1000; ++i)
        input_error = std::max(input_error, std::abs((mesh.x(Eigen::all, nodes) * basis.values(Eigen::VectorXd::Constant(1, -1.0 + i / 500.0))).norm() - 1.0));
    }
    ASSERT_EQ(arc.size(), 4u);
    const LevelSetFunction curve = facet_surface(mesh, topo, arc);
    Eigen::MatrixXd x_fixed = mesh.x;
    const OptimizeResult rf = optimize_mesh(mesh, topo, fixed_boundary(mesh, topo), {}, {}, x_fixed);
    Eigen::MatrixXd x = mesh.x;
    const OptimizeResult r = optimize_mesh(mesh, topo, fixed, slides, {}, x);
    EXPECT_TRUE(r.converged) << r.message;
    EXPECT_LT(r.energy, rf.energy);
    EXPECT_GT(r.min_det, 0.0);
    double off_curve = 0.0, off_circle = 0.0, moved = 0.0;
    for (std::int32_t node : boundary_nodes(mesh, topo)) {
      if (std::abs(mesh.x.col(node).norm() - 1.0) > 1e-12) continue;
      off_curve = std::max(off_curve, std::abs(curve.value(x.col(node))));
      off_circle = std::max(off_circle, std::abs(x.col(node).norm() - 1.0));
      moved = std::max(moved, (x.col(node) - mesh.x.col(node)).norm());
    }
    EXPECT_LT(off_curve, 1e-14);
    EXPECT_LE(off_circle, input_error + 1e-14);
    EXPECT_GT(input_error, 1e-6);  // the input's curve is not the circle: the bound above means something
    EXPECT_GT(moved, 1e-3);
    for (const FitTerm& t : slides)
      for (std::int32_t node : t.nodes) EXPECT_LT(std::abs(t.sigma.value(x.col(node))), 1e-14);
  }
}

// The sphere-in-a-box P2 mesh (examples/meshes): the box fixed, the sphere sliding on its own
// facets (no level set given). Its nodes end on the input's facets to 1e-10, so no farther
// from the exact sphere than the input's facets are (sampled 24 per direction, with 2% margin
// for the sampling), and the worst μ and F end below those with the sphere fixed. rtol 1e-8:
// Newton stalls near 1e-8 there (docs/optimize.md, What is left). The P3 case (elevated, its
// sphere nodes moved onto the sphere) converges at 1e-10, in tests/cli/check_optimize_p3.sh.
TEST(OptimizeSlide, SphereSlidesOnItsOwnCurvedFacets) {
  const std::string meshes = std::string(MESHMORPH_TEST_DATA) + "/../../examples/meshes/";
  {
    const int order = 2;
    const Mesh mesh = read_mesh(meshes + "sphere_in_box_p2.msh");
    const Topology topo = build_topology(mesh);
    std::vector<std::int32_t> sphere_facets;
    for (std::int32_t f : topo.boundary_facets) {
      const CellFacet cf = topo.facets[static_cast<std::size_t>(f)][0];
      const auto [blk, cell] = topo.locate(cf.cell);
      if (mesh.x.col(facet_nodes(mesh.cells[blk], cell, cf.local)[0]).norm() < 0.5) sphere_facets.push_back(f);
    }
    std::vector<std::int32_t> sphere;  // every node of those facets
    for (std::int32_t f : sphere_facets) {
      const CellFacet cf = topo.facets[static_cast<std::size_t>(f)][0];
      const auto [blk, cell] = topo.locate(cf.cell);
      for (std::int32_t n : facet_nodes(mesh.cells[blk], cell, cf.local)) sphere.push_back(n);
    }
    std::sort(sphere.begin(), sphere.end());
    sphere.erase(std::unique(sphere.begin(), sphere.end()), sphere.end());
    EXPECT_EQ(sphere, mesh.group_nodes(*mesh.find_group("sphere")));
    double input_error = 0.0;  // of the input's sphere facets from the sphere
    const int k = 24;
    for (std::int32_t f : sphere_facets) {
      const CellFacet cf = topo.facets[static_cast<std::size_t>(f)][0];
      const auto [blk, cell] = topo.locate(cf.cell);
      const Eigen::MatrixXd X = mesh.x(Eigen::all, facet_nodes(mesh.cells[blk], cell, cf.local));
      const LagrangeBasis& basis = lagrange_basis(ElementType::Triangle, order);
      for (int j = 0; j <= k; ++j)
        for (int i = 0; i + j <= k; ++i)
          input_error = std::max(input_error, std::abs((X * basis.values(Eigen::Vector2d(double(i) / k, double(j) / k))).norm() - 0.4));
    }
    std::vector<std::uint8_t> fixed = fixed_boundary(mesh, topo);
    Eigen::MatrixXd x_fixed = mesh.x;
    const OptimizeResult rf = optimize_mesh(mesh, topo, fixed, {}, {}, x_fixed);
    const std::vector<FitTerm> slides = boundary_slides(mesh, topo, sphere_facets, 30.0, true, fixed);
    ASSERT_EQ(slides.size(), 1u);
    EXPECT_EQ(slides[0].nodes.size(), sphere.size());
    Eigen::MatrixXd x = mesh.x;
    OptimizeOptions o;
    o.rtol = 1e-8;
    const OptimizeResult r = optimize_mesh(mesh, topo, fixed, slides, o, x);
    EXPECT_TRUE(rf.converged) << rf.message;
    EXPECT_TRUE(r.converged) << r.message;
    EXPECT_LT(r.mu_max, rf.mu_max);
    EXPECT_LT(r.energy, rf.energy);
    const LevelSetFunction own = facet_surface(mesh, topo, sphere_facets);
    double off_facets = 0.0, off_sphere = 0.0, moved = 0.0;
    for (std::int32_t n : sphere) {
      off_facets = std::max(off_facets, std::abs(own.value(x.col(n))));
      off_sphere = std::max(off_sphere, std::abs(x.col(n).norm() - 0.4));
      moved = std::max(moved, (x.col(n) - mesh.x.col(n)).norm());
    }
    EXPECT_LT(off_facets, 1e-10);
    EXPECT_LE(off_sphere, 1.02 * input_error);
    EXPECT_GT(moved, 1e-3);
  }
}

// Matrix-free Newton (Jacobi-preconditioned CG on the Hessian's action) and CHOLMOD on the
// assembled Hessian reach one minimiser: every node jittered, the boundary too, then fixed, so
// the optimum is not the grid (F > 0 there).
TEST(Optimize, MatrixFreeReachesTheMinimumOfCholesky) {
  for (auto [type, order] : {std::pair{ElementType::Quadrilateral, 3}, std::pair{ElementType::Triangle, 2},
                             std::pair{ElementType::Hexahedron, 2}, std::pair{ElementType::Tetrahedron, 2}}) {
    SCOPED_TRACE(std::string(name_of(type)) + " order " + std::to_string(order));
    const int n = 3;
    Mesh mesh = structured_mesh(type, order, n);
    const Topology topo = build_topology(mesh);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-0.1, 0.1);
    for (Eigen::Index i = 0; i < mesh.x.size(); ++i) mesh.x(i) += u(rng) / (n * order);
    ASSERT_EQ(count_invalid_cells(mesh), 0u);
    OptimizeOptions o;
    o.solver = OptimizeSolver::Cholesky;
    Eigen::MatrixXd x_direct = mesh.x, x_free = mesh.x;
    const OptimizeResult direct = optimize_mesh(mesh, topo, fixed_boundary(mesh, topo), {}, o, x_direct);
    o.solver = OptimizeSolver::MatrixFree;
    const OptimizeResult free = optimize_mesh(mesh, topo, fixed_boundary(mesh, topo), {}, o, x_free);
    ASSERT_TRUE(direct.converged) << direct.message;
    ASSERT_TRUE(free.converged) << free.message;
    EXPECT_EQ(direct.solver, "cholmod");
    EXPECT_EQ(free.solver, "matrix-free");
    EXPECT_GT(free.energy, 1e-4);
    EXPECT_NEAR(free.energy, direct.energy, 1e-10 * direct.energy);
    EXPECT_LT((x_free - x_direct).cwiseAbs().maxCoeff(), 1e-6);
    EXPECT_GT(free.min_det, 0.0);
    EXPECT_LE(free.newton, 30);
  }
}

// The two-level preconditioner (block Jacobi plus the vertex hats' Galerkin matrix) against
// block Jacobi alone: the same minimiser, in a fraction of the CG iterations (P2 hexahedra and
// P3 tetrahedra, 4 cubes a side, interior jittered, boundary fixed).
TEST(Optimize, TwoLevelPreconditioningCutsTheCgIterations) {
  for (auto [type, order, jitter] : {std::tuple{ElementType::Hexahedron, 2, 0.15}, std::tuple{ElementType::Tetrahedron, 3, 0.05}}) {
    SCOPED_TRACE(std::string(name_of(type)) + " order " + std::to_string(order));
    const int n = 4;
    const Mesh mesh = structured_mesh(type, order, n);
    const Topology topo = build_topology(mesh);
    const Eigen::MatrixXd x0 = jitter_interior(mesh, topo, jitter, 1.0 / (n * order), 3);
    const std::vector<FitTerm> no_terms;
    FitOptions o;
    o.quadrature = QuadratureFamily::Lobatto;
    NewtonOptions no;
    // Above the energy's rounding floor: at the grid F is 1e-17 of round-off, and where the
    // decrements stall (1e-18 to 1e-24) depends on the rounding of the coarse solves.
    no.decrement_tolerance = 1e-16;
    std::array<NewtonStats, 2> stats;
    std::array<Eigen::MatrixXd, 2> x;
    for (int two_level = 0; two_level < 2; ++two_level) {
      FitProblem<3> P(mesh, topo, no_terms, fixed_boundary(mesh, topo), o, x0, {}, true);
      P.remember_current();  // the line search's reference, as optimize_mesh sets it
      KrylovNewtonOptions ko;
      ko.two_level = two_level == 1;
      stats[static_cast<std::size_t>(two_level)] = newton_matrix_free(P, no, ko);
      x[static_cast<std::size_t>(two_level)] = P.state();
      EXPECT_TRUE(stats[static_cast<std::size_t>(two_level)].converged) << stats[static_cast<std::size_t>(two_level)].message;
    }
    EXPECT_LT((x[1] - x[0]).cwiseAbs().maxCoeff(), 1e-8);  // the grid: F = 0 there
    EXPECT_LT(4 * stats[1].krylov_iterations, 3 * stats[0].krylov_iterations)  // 29 vs 44, 61 vs 113 when measured
        << stats[1].krylov_iterations << " CG iterations with the coarse level, " << stats[0].krylov_iterations << " without";
  }
}

// Sliding on the planes of the boundary (nodes on faces and on the edges where two meet), the
// interior jittered: the matrix-free action of the constrained Hessian (P H P plus the normal
// stiffness) and its node blocks lead Newton to CHOLMOD's minimiser.
TEST(Optimize, MatrixFreeSlidesReachTheMinimumOfCholesky) {
  for (auto [type, order] : {std::pair{ElementType::Quadrilateral, 3}, std::pair{ElementType::Hexahedron, 2}}) {
    SCOPED_TRACE(std::string(name_of(type)) + " order " + std::to_string(order));
    const int n = 3;
    const Mesh mesh = structured_mesh(type, order, n);
    const Topology topo = build_topology(mesh);
    std::vector<std::uint8_t> fixed(static_cast<std::size_t>(mesh.dim) * mesh.n_nodes(), 0);
    const std::vector<FitTerm> slides = boundary_slides(mesh, topo, topo.boundary_facets, 30.0, false, fixed);
    ASSERT_FALSE(slides.empty());
    // The boundary too: its nodes start off their place on the planes they slide on.
    Mesh moved = mesh;
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-0.1, 0.1);
    for (Eigen::Index i = 0; i < moved.x.size(); ++i)
      if (!fixed[static_cast<std::size_t>(i)]) moved.x(i) += u(rng) / (n * order);
    OptimizeOptions o;
    o.solver = OptimizeSolver::Cholesky;
    Eigen::MatrixXd x_direct = moved.x, x_free = moved.x;
    const OptimizeResult direct = optimize_mesh(mesh, topo, fixed, slides, o, x_direct);
    o.solver = OptimizeSolver::MatrixFree;
    const OptimizeResult free = optimize_mesh(mesh, topo, fixed, slides, o, x_free);
    ASSERT_TRUE(direct.converged) << direct.message;
    ASSERT_TRUE(free.converged) << free.message;
    EXPECT_EQ(free.solver, "matrix-free");
    EXPECT_GT(free.energy0, free.energy + 1e-3);  // the jitter was undone
    EXPECT_NEAR(free.energy, direct.energy, 1e-10 * std::max(1.0, direct.energy));
    EXPECT_LT((x_free - x_direct).cwiseAbs().maxCoeff(), 1e-6);
    EXPECT_LT((x_free - mesh.x).cwiseAbs().maxCoeff(), 1e-6);  // the grid, its own minimiser
  }
}

}  // namespace
}  // namespace meshmorph
