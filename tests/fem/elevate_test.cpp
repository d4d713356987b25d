// SPDX-License-Identifier: MIT
#include "meshmorph/fem/elevate.h"

#include <algorithm>
#include <string>
#include <tuple>

#include <gtest/gtest.h>

#include "meshmorph/fem/structured.h"
#include "meshmorph/fem/trace.h"
#include "meshmorph/fem/validity.h"
#include "meshmorph/mesh/topology.h"
#include "support/element_cases.h"

namespace meshmorph {
namespace {

using test::ElementCase;

class ElevateSweep : public ::testing::TestWithParam<ElementCase> {};

// Node count of an n-per-side structured mesh of order p: the (pn+1)^d lattice.
TEST_P(ElevateSweep, SharesNodesBetweenNeighboursAndPlacesThemOnTheLattice) {
  const auto [type, p] = GetParam();
  const int n = 2;
  const auto mesh = structured_mesh(type, p, n);
  const int dim = topological_dim(type);
  const int side = p * n + 1;
  EXPECT_EQ(mesh.n_nodes(), static_cast<std::size_t>(dim == 2 ? side * side : side * side * side));
  for (Eigen::Index i = 0; i < mesh.x.cols(); ++i)
    for (int k = 0; k < dim; ++k) {
      const double s = mesh.x(k, i) * p * n;
      EXPECT_NEAR(s, std::round(s), 1e-12);
    }
  EXPECT_EQ(count_invalid_cells(mesh), 0u);
  // Facets were elevated with the same nodes as the cells: every facet node is a boundary node.
  const auto topo = build_topology(mesh);
  const auto bnd = boundary_nodes(mesh, topo);
  for (auto v : mesh.facets[0].nodes) EXPECT_TRUE(std::binary_search(bnd.begin(), bnd.end(), v));
  EXPECT_EQ(mesh.facets[0].order, p);
}

INSTANTIATE_TEST_SUITE_P(AllCells, ElevateSweep, ::testing::ValuesIn(test::all_cell_cases()), test::CaseName());
INSTANTIATE_TEST_SUITE_P(Prisms, ElevateSweep,
                         ::testing::Values(ElementCase{ElementType::Prism, 1}, ElementCase{ElementType::Prism, 2},
                                           ElementCase{ElementType::Prism, 3}, ElementCase{ElementType::Prism, 4}),
                         test::CaseName());

TEST(Elevate, InStepsEqualsAtOnce) {
  for (auto type : {ElementType::Triangle, ElementType::Quadrilateral, ElementType::Tetrahedron, ElementType::Hexahedron}) {
    const int p = max_order_of(type);
    const auto once = elevate_order(structured_mesh(type, 1, 2), p);
    const auto steps = elevate_order(elevate_order(structured_mesh(type, 1, 2), 2), p);
    ASSERT_EQ(once.n_nodes(), steps.n_nodes());
    const auto& a = once.cells[0];
    const auto& b = steps.cells[0];
    for (std::size_t c = 0; c < a.n_cells(); ++c)
      for (int j = 0; j < a.n_nodes_per_cell(); ++j)
        EXPECT_LT((once.x.col(a.cell(c)[j]) - steps.x.col(b.cell(c)[j])).norm(), 1e-14) << name_of(type);
  }
}

TEST(Elevate, KeepsLinearNodesAndTagsAndRefusesToLower) {
  const auto lin = structured_mesh(ElementType::Triangle, 1, 3);
  const auto p2 = elevate_order(lin, 2);
  EXPECT_EQ(p2.x.leftCols(lin.x.cols()), lin.x);
  EXPECT_TRUE(std::equal(lin.node_tags.begin(), lin.node_tags.end(), p2.node_tags.begin()));
  EXPECT_EQ(p2.node_tags.back(), static_cast<std::int64_t>(p2.n_nodes()));
  EXPECT_THROW(elevate_order(p2, 1), std::invalid_argument);
}

// A field of the old order is interpolated exactly: (bi)linear on P1 cells, quadratic on
// P2 triangles raised to P4.
TEST(Elevate, InterpolatesNodeFieldsWithTheOldBasis) {
  const auto field = [](const Eigen::VectorXd& x, int order) {
    return order == 1 ? 0.5 + x(0) - 2 * x(1) : x(0) * x(1) - x(1) * x(1) + 0.25;
  };
  for (const auto& [type, from, to] : {std::tuple{ElementType::Triangle, 1, 3}, std::tuple{ElementType::Tetrahedron, 1, 2},
                                       std::tuple{ElementType::Triangle, 2, 4}}) {
    SCOPED_TRACE(std::string(name_of(type)) + " " + std::to_string(from) + " -> " + std::to_string(to));
    Mesh m = structured_mesh(type, from, 2);
    Eigen::VectorXd phi(m.x.cols());
    for (Eigen::Index i = 0; i < phi.size(); ++i) phi(i) = field(m.x.col(i), from);
    m.node_fields["phi"] = phi;
    const Mesh e = elevate_order(m, to);
    ASSERT_EQ(e.node_fields.count("phi"), 1u);
    ASSERT_EQ(static_cast<std::size_t>(e.node_fields.at("phi").size()), e.n_nodes());
    for (Eigen::Index i = 0; i < e.x.cols(); ++i) EXPECT_NEAR(e.node_fields.at("phi")(i), field(e.x.col(i), from), 1e-14);
  }
}

// A block below the order and none above: raise (also where the highest block is at it).
TEST(Elevate, BelowOrderLooksAtEveryBlock) {
  const Mesh p1 = structured_mesh(ElementType::Triangle, 1, 2);
  Mesh mixed = elevate_order(p1, 3);  // the P1 nodes keep their indices
  EXPECT_TRUE(below_order(p1, 3));
  EXPECT_FALSE(below_order(p1, 1));
  EXPECT_FALSE(below_order(mixed, 3));
  mixed.cells.push_back(p1.cells[0]);
  EXPECT_TRUE(below_order(mixed, 3));
  EXPECT_FALSE(below_order(mixed, 2));  // the P3 block is above: nothing to raise
  EXPECT_EQ(elevate_order(mixed, 3).cells.size(), 2u);
  for (const CellBlock& b : elevate_order(mixed, 3).cells) EXPECT_EQ(b.order, 3);
}

}  // namespace
}  // namespace meshmorph
