// SPDX-License-Identifier: MIT
#include "meshmorph/methods/fit.h"

#include <cmath>
#include <random>
#include <tuple>

#include <gtest/gtest.h>

#include "meshmorph/fem/elevate.h"
#include "meshmorph/fem/jacobian.h"
#include "meshmorph/fem/reference_element.h"
#include "meshmorph/fem/structured.h"
#include "meshmorph/fem/trace.h"
#include "meshmorph/fem/validity.h"
#include "meshmorph/io/mesh_io.h"
#include "methods/detail/fit_problem.h"

namespace meshmorph {
namespace {

LevelSetFunction circle(double r) {
  LevelSet ls;
  ls.shape = SphereLevelSet{Eigen::Vector2d(0.5, 0.5), r};
  return LevelSetFunction(ls, 2);
}

std::vector<std::uint8_t> fixed_boundary(const Mesh& mesh, const Topology& topo) {
  std::vector<std::uint8_t> fixed(static_cast<std::size_t>(mesh.dim) * mesh.n_nodes(), 0);
  for (std::int32_t node : boundary_nodes(mesh, topo)) std::fill_n(fixed.begin() + mesh.dim * node, mesh.dim, 1);
  return fixed;
}

// The interface of a circle in a structured mesh, corrected by eq. 12 and split where needed.
struct Marked {
  Mesh mesh;
  std::vector<std::uint8_t> eta;
  std::size_t split = 0;
};
Marked mark(Mesh mesh, const LevelSetFunction& sigma) {
  Topology topo = build_topology(mesh);
  std::vector<std::int32_t> to_split;
  std::vector<std::uint8_t> eta = correct_indicators(topo, material_indicators(mesh, sigma), to_split);
  const std::size_t n = to_split.size();
  if (n > 0) mesh = split_cells(mesh, topo, to_split, eta);
  return {std::move(mesh), std::move(eta), n};
}

// Eq. 10 then eq. 12 (and splits): no cell keeps two facets on the interface.
TEST(FitInterface, CorrectedIndicatorsLeaveOneInterfaceFacetPerCell) {
  for (ElementType type : {ElementType::Triangle, ElementType::Quadrilateral}) {
    const Mesh mesh = structured_mesh(type, 1, 10);
    const LevelSetFunction sigma = circle(0.3);
    const std::vector<std::uint8_t> raw = material_indicators(mesh, sigma);
    const std::vector<int> before = interface_facet_counts(build_topology(mesh), raw);
    const Marked m = mark(mesh, sigma);
    const Topology topo = build_topology(m.mesh);
    const std::vector<int> after = interface_facet_counts(topo, m.eta);
    EXPECT_LE(*std::max_element(after.begin(), after.end()), 1) << name_of(type);
    EXPECT_EQ(count_invalid_cells(m.mesh), 0u);
    EXPECT_GT(facets_nodes(interface_facets(m.mesh, topo, m.eta)).size(), 8u);
    if (type == ElementType::Quadrilateral) {  // a staircase: eq. 10 marks two facets of its corner cells
      EXPECT_GT(*std::max_element(before.begin(), before.end()), 1);
      EXPECT_GT(m.split, 0u);
    }
  }
}

// A split adds centroid nodes: nodal fields grow with them, and a linear field stays linear.
TEST(FitInterface, SplitsCarryNodalFieldsToTheNewNodes) {
  Mesh mesh = structured_mesh(ElementType::Quadrilateral, 1, 3);
  mesh.node_fields["f"] = (mesh.x.row(0) + 2.0 * mesh.x.row(1)).transpose();
  const Topology topo = build_topology(mesh);
  std::vector<std::uint8_t> eta(mesh.n_cells(), 0);
  eta[4] = 1;  // the middle cell: all four facets on the interface, split from its centroid
  const Mesh split = split_cells(mesh, topo, {4}, eta);
  ASSERT_EQ(split.n_nodes(), mesh.n_nodes() + 1);
  const Eigen::VectorXd& f = split.node_fields.at("f");
  ASSERT_EQ(f.size(), static_cast<Eigen::Index>(split.n_nodes()));
  for (std::size_t i = 0; i < split.n_nodes(); ++i)
    EXPECT_NEAR(f[i], split.x(0, i) + 2.0 * split.x(1, i), 1e-14) << "node " << i;
}

// The derivatives of F = F_μ + w Σ σ² against differences of F at a state with σ ≠ 0.
TEST(FitProblem, GradientAndHessianMatchDifferences) {
  const Mesh mesh = elevate_order(structured_mesh(ElementType::Triangle, 1, 4), 2);
  const Topology topo = build_topology(mesh);
  const LevelSetFunction sigma = circle(0.3);
  std::vector<FitTerm> terms{{sigma, facets_nodes(interface_facets(mesh, topo, material_indicators(mesh, sigma)))}};
  const std::vector<std::uint8_t> fixed = fixed_boundary(mesh, topo);
  FitOptions o;
  FitProblem<2> P(mesh, topo, terms, fixed, o, mesh.x);
  P.penalty().weight = 7.0;
  Assembly a;
  P.evaluate(HessianMode::Exact, a);
  const Eigen::Index n = a.gradient.size();
  ASSERT_GT(n, 0);
  std::mt19937 rng(11);
  std::uniform_int_distribution<Eigen::Index> pick(0, n - 1);
  const double h = 1e-6;
  for (int trial = 0; trial < 12; ++trial) {
    const Eigen::Index i = pick(rng);
    const Eigen::VectorXd e = Eigen::VectorXd::Unit(n, i);
    const double fd = (P.trial_value(e, h) - P.trial_value(e, -h)) / (2 * h);
    EXPECT_NEAR(a.gradient[i], fd, 1e-6 * std::max(1.0, std::abs(fd))) << i;
    FitProblem<2> plus(mesh, topo, terms, fixed, o, mesh.x), minus(mesh, topo, terms, fixed, o, mesh.x);
    plus.penalty().weight = minus.penalty().weight = P.penalty().weight;
    plus.accept(e, h);
    minus.accept(e, -h);
    Assembly ap, am;
    plus.evaluate(HessianMode::Exact, ap);
    minus.evaluate(HessianMode::Exact, am);
    const Eigen::VectorXd column = (ap.gradient - am.gradient) / (2 * h);
    EXPECT_LE((Eigen::VectorXd(a.hessian.col(i)) - column).norm(), 1e-5 * std::max(1.0, column.norm())) << i;
  }
}

// A circle interface in triangle meshes of orders 1–2: fitted to 1e-9, valid.
TEST(Fit, FitsACircleInterface) {
  for (int order : {1, 2}) {
    const LevelSetFunction sigma = circle(0.3);
    Marked m = mark(structured_mesh(ElementType::Triangle, 1, 10), sigma);
    const Mesh mesh = order > 1 ? elevate_order(m.mesh, order) : m.mesh;
    const Topology topo = build_topology(mesh);
    std::vector<FitTerm> terms{{sigma, facets_nodes(interface_facets(mesh, topo, m.eta))}};
    FitOptions o;
    o.eps_sigma = 1e-9;
    Eigen::MatrixXd x = mesh.x;
    const FitResult r = fit_to_level_sets(mesh, topo, terms, fixed_boundary(mesh, topo), o, x);
    ASSERT_TRUE(r.converged) << "order " << order << ": " << r.message;
    EXPECT_LE(r.fit_error, 1e-9);
    EXPECT_GT(r.fit_error0, 1e-3);
    EXPECT_GT(r.min_det, 0.0);
    Mesh moved = mesh;
    moved.x = x;
    EXPECT_EQ(count_invalid_cells(moved), 0u);
    for (std::int32_t s : terms[0].nodes) EXPECT_LE(std::abs(sigma.value(x.col(s))), 1e-9);
  }
}

// The crowding flips (ours, after eq. 12) lower the number of cells with two or more
// interface facets; without them (reduce_crowding = false, as under flat_edges) eq. 12 alone
// leaves more: 4 against 12 on the quadrilaterals and 32 against 104 on the hexahedra here.
TEST(FitInterface, CrowdingFlipsLowerTheTwoFacetCells) {
  for (auto [type, n, r] : {std::tuple{ElementType::Quadrilateral, 10, 0.3}, std::tuple{ElementType::Hexahedron, 8, 0.35}}) {
    SCOPED_TRACE(name_of(type));
    const Mesh mesh = structured_mesh(type, 1, n);
    const Topology topo = build_topology(mesh);
    LevelSet ls;
    ls.shape = SphereLevelSet{Eigen::VectorXd::Constant(mesh.dim, 0.5), r};
    const std::vector<std::uint8_t> raw = material_indicators(mesh, LevelSetFunction(ls, mesh.dim));
    std::vector<std::int32_t> split_with, split_without;
    const std::vector<std::uint8_t> with = correct_indicators(topo, raw, split_with, true);
    const std::vector<std::uint8_t> without = correct_indicators(topo, raw, split_without, false);
    const auto crowded = [&](const std::vector<std::uint8_t>& eta) {
      const std::vector<int> k = interface_facet_counts(topo, eta);
      return static_cast<std::size_t>(std::count_if(k.begin(), k.end(), [](int m) { return m >= 2; }));
    };
    EXPECT_EQ(crowded(with), split_with.size());
    EXPECT_EQ(crowded(without), split_without.size());
    EXPECT_LT(crowded(with), crowded(without));
  }
}

// The crowding pass (cells and vertex stars) leaves no tetrahedron of a structured mesh with
// two interface facets on a sphere, where eq. 12 alone leaves some.
TEST(FitInterface, VertexStarFlipsClearTheTetrahedraOfASphere) {
  const Mesh mesh = structured_mesh(ElementType::Tetrahedron, 1, 6);
  const Topology topo = build_topology(mesh);
  LevelSet ls;
  ls.shape = SphereLevelSet{Eigen::Vector3d::Constant(0.5), 0.3};
  const std::vector<std::uint8_t> raw = material_indicators(mesh, LevelSetFunction(ls, 3));
  std::vector<std::int32_t> with, without;
  correct_indicators(topo, raw, with, true, true);
  correct_indicators(topo, raw, without, true, false);
  EXPECT_GT(without.size(), 0u);
  EXPECT_EQ(with.size(), 0u);
}

// Fit's target choice measures the input against the ideal target: squares and cubes are
// ideal (0), a right isosceles triangle has mu2 = 2/sqrt(3) - 1 against the equilateral one.
TEST(FitChoices, MeanShapeDistortionOfStructuredMeshes) {
  EXPECT_NEAR(mean_shape_distortion(structured_mesh(ElementType::Quadrilateral, 1, 4)), 0.0, 1e-14);
  EXPECT_NEAR(mean_shape_distortion(structured_mesh(ElementType::Hexahedron, 1, 3)), 0.0, 1e-14);
  EXPECT_NEAR(mean_shape_distortion(structured_mesh(ElementType::Triangle, 1, 4)), 2.0 / std::sqrt(3.0) - 1.0, 1e-12);
}

// Flat edges: a cell's samples on the edge (corner in 2D) where two of its fitted facets
// meet, and no others; none between opposite facets or on a single fitted facet. (Linear
// tetrahedra are left out: there a facet across the cube, with its vertices on the two
// planes, counts as fitted too.)
TEST(FitInterface, FlatEdgesAreTheEdgesBetweenTwoFittedFacets) {
  for (ElementType type : {ElementType::Quadrilateral, ElementType::Hexahedron, ElementType::Tetrahedron})
    for (int order = is_simplex(type) ? 2 : 1; order <= 3; ++order) {
      SCOPED_TRACE(std::string(name_of(type)) + " order " + std::to_string(order));
      const Mesh mesh = structured_mesh(type, order, 1);
      const int d = mesh.dim;
      const auto on = [&](int axis, double value) {  // the nodes on the plane x_axis = value
        std::vector<std::uint8_t> f(mesh.n_nodes(), 0);
        for (Eigen::Index j = 0; j < mesh.x.cols(); ++j) f[static_cast<std::size_t>(j)] = std::abs(mesh.x(axis, j) - value) < 1e-12;
        return f;
      };
      const auto join = [](std::vector<std::uint8_t> a, const std::vector<std::uint8_t>& b) {
        for (std::size_t j = 0; j < a.size(); ++j) a[j] |= b[j];
        return a;
      };
      // The planes x = 1 and x_{d−1} = 0: the structured simplices have facets on both.
      const std::vector<std::uint8_t> bottom = on(d - 1, 0.0), both = join(on(0, 1.0), bottom);
      EXPECT_EQ(flat_edges(mesh, bottom).cells, 0u);
      if (!is_simplex(type) && order > 1) {  // at order 1 the side facets' nodes are all on the two
        EXPECT_EQ(flat_edges(mesh, join(bottom, on(d - 1, 1.0))).cells, 0u);
      }

      const FlatEdges flat = flat_edges(mesh, both);
      // Expected: the samples whose image lies on x = 1 and x_{d−1} = 0, in the cells that
      // have a facet on each of the two planes.
      std::size_t cells = 0;
      for (std::size_t b = 0; b < mesh.cells.size(); ++b) {
        const CellBlock& block = mesh.cells[b];
        const ShapeTable& samples = validity_samples(block.type, block.order);
        for (std::size_t c = 0; c < block.n_cells(); ++c) {
          const Eigen::MatrixXd image = cell_coordinates(mesh, block, c) * samples.N;
          const std::int32_t k = flat.mask_of_cell[b][c];
          std::size_t expected = 0, flagged = 0;
          for (int q = 0; q < samples.n_points(); ++q) {
            const bool edge = std::abs(image(0, q) - 1) < 1e-9 && std::abs(image(d - 1, q)) < 1e-9;
            const bool flag = k >= 0 && flat.masks[static_cast<std::size_t>(k)][static_cast<std::size_t>(q)];
            expected += edge;
            flagged += flag;
            if (k >= 0) {
              EXPECT_EQ(flag, edge) << "cell " << c << " sample " << q;
            }
          }
          if (k >= 0) {
            ++cells;
            EXPECT_GT(flagged, 0u);
          } else if (expected > 0) {  // a cell with an edge on the line but a facet on one plane at most
            std::size_t facets = 0;
            for (const std::vector<int>& f : reference_element(block.type, block.order).facet_nodes)
              facets += std::all_of(f.begin(), f.end(), [&](int a) { return both[static_cast<std::size_t>(block.nodes[c * block.n_nodes_per_cell() + a])] != 0; });
            EXPECT_LT(facets, 2u) << "cell " << c;
          }
        }
      }
      EXPECT_EQ(flat.cells, cells);
      EXPECT_GT(cells, 0u);
    }
}

// A corner whose three edges are fitted, without two fitted facets: that corner only.
TEST(FitInterface, ACornerWithThreeFittedEdgesIsFlat) {
  for (ElementType type : {ElementType::Hexahedron, ElementType::Tetrahedron})
    for (int order = 1; order <= 3; ++order) {
      SCOPED_TRACE(std::string(name_of(type)) + " order " + std::to_string(order));
      const Mesh mesh = structured_mesh(type, order, 1);
      std::vector<std::uint8_t> fitted(mesh.n_nodes(), 0);  // the nodes with two coordinates 1
      for (Eigen::Index j = 0; j < mesh.x.cols(); ++j)
        fitted[static_cast<std::size_t>(j)] = (mesh.x.col(j).array() > 1 - 1e-12).count() >= 2;
      const FlatEdges flat = flat_edges(mesh, fitted);
      const CellBlock& block = mesh.cells[0];
      const ShapeTable& samples = validity_samples(block.type, block.order);
      std::size_t cells = 0;
      for (std::size_t c = 0; c < block.n_cells(); ++c) {
        const std::int32_t k = flat.mask_of_cell[0][c];
        if (k < 0) continue;
        ++cells;
        const Eigen::MatrixXd image = cell_coordinates(mesh, block, c) * samples.N;
        for (int q = 0; q < samples.n_points(); ++q)
          EXPECT_EQ(flat.masks[static_cast<std::size_t>(k)][static_cast<std::size_t>(q)] != 0,
                    (image.col(q).array() > 1 - 1e-9).all())
              << "cell " << c << " sample " << q;
      }
      // The hexahedron; no structured tetrahedron has its three edges at (1, 1, 1) on those
      // lines (their edges there include a face or body diagonal).
      EXPECT_EQ(cells, type == ElementType::Hexahedron ? 1u : 0u);
    }
}

// Nodes already on the level set (the line x = 0.5 through a column of nodes) and a mesh
// at its metric's minimum: nothing moves.
TEST(Fit, AFittedOptimalMeshIsAFixedPoint) {
  const Mesh mesh = structured_mesh(ElementType::Quadrilateral, 2, 4);
  const Topology topo = build_topology(mesh);
  LevelSet plane;
  plane.shape = PlaneLevelSet{Eigen::Vector2d(0.5, 0.0), Eigen::Vector2d(1.0, 0.0)};
  const LevelSetFunction sigma(plane, 2);
  std::vector<std::int32_t> on;
  for (Eigen::Index i = 0; i < mesh.x.cols(); ++i)
    if (std::abs(mesh.x(0, i) - 0.5) < 1e-14) on.push_back(static_cast<std::int32_t>(i));
  std::vector<FitTerm> terms{{sigma, on}};
  Eigen::MatrixXd x = mesh.x;
  const FitResult r = fit_to_level_sets(mesh, topo, terms, fixed_boundary(mesh, topo), FitOptions{}, x);
  EXPECT_TRUE(r.converged);
  EXPECT_EQ(r.newton, 0);
  EXPECT_LE((x - mesh.x).cwiseAbs().maxCoeff(), 1e-14);
}

// Trimming (§4.2): the cells outside a circle go, the nodes on the new boundary are fitted to
// it; the rest of the boundary (none here) and every kept cell stay valid.
TEST(Fit, TrimsTheMeshAndFitsTheNewBoundary) {
  const LevelSetFunction sigma = circle(0.35);
  Mesh mesh = structured_mesh(ElementType::Triangle, 1, 12);
  Topology topo = build_topology(mesh);
  std::vector<std::int32_t> to_split;
  const std::vector<std::uint8_t> keep = correct_indicators(topo, material_indicators(mesh, sigma), to_split);
  std::vector<std::vector<std::uint8_t>> cut;
  const Mesh trimmed = elevate_order(trim_cells(mesh, topo, keep, cut), 2);
  ASSERT_EQ(cut.size(), trimmed.n_cells());
  EXPECT_LT(trimmed.n_cells(), mesh.n_cells());
  for (Eigen::Index i = 0; i < trimmed.x.cols(); ++i) EXPECT_LT(sigma.value(trimmed.x.col(i)), 0.2);  // nothing far outside
  const Topology t2 = build_topology(trimmed);
  const std::vector<std::int32_t> on = facets_nodes(cut_facets(trimmed, cut));
  EXPECT_EQ(on, boundary_nodes(trimmed, t2)) << "the whole new boundary is cut";
  std::vector<FitTerm> terms{{sigma, on}};
  std::vector<std::uint8_t> fixed(2 * trimmed.n_nodes(), 0);
  FitOptions o;
  o.eps_sigma = 1e-9;
  Eigen::MatrixXd x = trimmed.x;
  const FitResult r = fit_to_level_sets(trimmed, t2, terms, fixed, o, x);
  ASSERT_TRUE(r.converged) << r.message;
  Mesh moved = trimmed;
  moved.x = x;
  EXPECT_EQ(count_invalid_cells(moved), 0u);
  for (std::int32_t s : on) EXPECT_LE(std::abs(sigma.value(x.col(s))), 1e-9);
}

// The hybrid layer mesh (prisms and hexahedra under tetrahedra, pyramids between;
// tests/data/hybrid_layer.geo): the inner nodes of the layer's top (z = 0.1, prisms' and
// hexahedra's top faces and the pyramids' bases) fitted to the plane z = 0.13 against the
// input's shapes, the boundary fixed: fitted to 1e-9, valid.
TEST(Fit, FitsTheTopOfAHybridLayer) {
  const Mesh mesh = read_mesh(std::string(MESHMORPH_TEST_DATA) + "/hybrid_layer.msh");
  const Topology topo = build_topology(mesh);
  const std::vector<std::uint8_t> fixed = fixed_boundary(mesh, topo);
  std::vector<std::int32_t> top;
  for (Eigen::Index i = 0; i < mesh.x.cols(); ++i)
    if (std::abs(mesh.x(2, i) - 0.1) < 1e-12 && !fixed[static_cast<std::size_t>(3 * i)]) top.push_back(static_cast<std::int32_t>(i));
  ASSERT_EQ(top.size(), 6u);
  LevelSet plane;
  plane.shape = PlaneLevelSet{Eigen::Vector3d(0.0, 0.0, 0.13), Eigen::Vector3d(0.0, 0.0, 1.0)};
  std::vector<FitTerm> terms{{LevelSetFunction(plane, 3), top}};
  FitOptions o;
  o.eps_sigma = 1e-9;
  o.target = TargetKind::Input;
  Eigen::MatrixXd x = mesh.x;
  const FitResult r = fit_to_level_sets(mesh, topo, terms, fixed, o, x);
  ASSERT_TRUE(r.converged) << r.message;
  EXPECT_NEAR(r.fit_error0, 0.03, 1e-12);
  EXPECT_LE(r.fit_error, 1e-9);
  EXPECT_GT(r.min_det, 0.0);
  Mesh moved = mesh;
  moved.x = x;
  EXPECT_EQ(count_invalid_cells(moved), 0u);
  for (std::int32_t s : top) EXPECT_NEAR(x(2, s), 0.13, 1e-9);
}

}  // namespace
}  // namespace meshmorph
