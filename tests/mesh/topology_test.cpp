// SPDX-License-Identifier: MIT
#include "meshmorph/mesh/topology.h"

#include <algorithm>

#include <gtest/gtest.h>

#include "meshmorph/error.h"

namespace meshmorph {
namespace {

// Two triangles of the unit square, with the diagonal 0–2 shared and two tagged sides.
Mesh two_triangles() {
  Mesh m;
  m.dim = 2;
  m.x.resize(2, 4);
  m.x << 0, 1, 1, 0,  //
      0, 0, 1, 1;
  m.node_tags = {10, 20, 30, 40};
  CellBlock tris{ElementType::Triangle, 1, {}, {}, {}};
  const std::int32_t t0[] = {0, 1, 2}, t1[] = {0, 2, 3};
  tris.push_back(t0, 7);
  tris.push_back(t1, 7);
  m.cells.push_back(tris);
  CellBlock lines{ElementType::Line, 1, {}, {}, {}};
  const std::int32_t l0[] = {0, 1}, l1[] = {2, 3};
  lines.push_back(l0, 1);
  lines.push_back(l1, 2);
  m.facets.push_back(lines);
  m.groups = {{1, 1, "bottom"}, {1, 2, "top"}, {2, 7, "domain"}};
  return m;
}

TEST(Topology, CountsEdgesFacetsAndBoundary) {
  const auto topo = build_topology(two_triangles());
  EXPECT_EQ(topo.edges.size(), 5u);
  EXPECT_EQ(topo.facets.size(), 5u);
  EXPECT_EQ(topo.boundary_facets.size(), 4u);
  EXPECT_EQ(topo.boundary_corners, (std::vector<std::int32_t>{0, 1, 2, 3}));
  // The diagonal joins the two cells through their local facets 2 (t0: 2→0) and 0 (t1: 0→2).
  EXPECT_EQ(topo.cell_neighbors[2], 1);
  EXPECT_EQ(topo.cell_neighbors[3], 0);
  EXPECT_EQ(topo.cell_neighbors[0], -1);
}

TEST(Topology, NodeAdjacencyIsSymmetricAndIncludesItself) {
  const auto topo = build_topology(two_triangles());
  for (std::size_t i = 0; i + 1 < topo.node_node_offset.size(); ++i) {
    const auto* row = topo.node_nodes.data() + topo.node_node_offset[i];
    const auto* end = topo.node_nodes.data() + topo.node_node_offset[i + 1];
    EXPECT_TRUE(std::binary_search(row, end, static_cast<std::int32_t>(i)));
    for (const auto* j = row; j != end; ++j) {
      const auto* r2 = topo.node_nodes.data() + topo.node_node_offset[static_cast<std::size_t>(*j)];
      const auto* e2 = topo.node_nodes.data() + topo.node_node_offset[static_cast<std::size_t>(*j) + 1];
      EXPECT_TRUE(std::binary_search(r2, e2, static_cast<std::int32_t>(i)));
    }
  }
  // Nodes 1 and 3 share no cell.
  const auto* row1 = topo.node_nodes.data() + topo.node_node_offset[1];
  EXPECT_FALSE(std::binary_search(row1, topo.node_nodes.data() + topo.node_node_offset[2], 3));
  EXPECT_EQ(topo.node_cell_offset[1] - topo.node_cell_offset[0], 2);  // node 0 is in both cells
}

// A strip of 2 × 5000 nodes ((i, 0) is node 2i, (i, 1) node 2i + 1), two triangles per
// square, the cells listed from the far end: node rows span several of the chunks that
// build_topology fills in parallel.
TEST(Topology, NodeRowsOfALongStripAreTheSortedNeighboursOfEachNode) {
  constexpr std::int32_t n = 5000;
  Mesh m;
  m.dim = 2;
  m.x.resize(2, 2 * n);
  for (std::int32_t i = 0; i < n; ++i) {
    m.x.col(2 * i) << i, 0;
    m.x.col(2 * i + 1) << i, 1;
  }
  CellBlock tris{ElementType::Triangle, 1, {}, {}, {}};
  for (std::int32_t i = n - 2; i >= 0; --i) {
    const std::int32_t lower[] = {2 * i, 2 * i + 2, 2 * i + 3}, upper[] = {2 * i, 2 * i + 3, 2 * i + 1};
    tris.push_back(lower, 1);
    tris.push_back(upper, 1);
  }
  m.cells.push_back(tris);
  const auto topo = build_topology(m);
  ASSERT_EQ(topo.node_node_offset.size(), static_cast<std::size_t>(2 * n + 1));
  for (std::int32_t i = 0; i < n; ++i) {
    // Square i is cut by its diagonal 2i–2i+3: bottom node 2i meets 2i − 2 and 2i + 1 through
    // square i − 1's lower triangle, 2i + 2, 2i + 3 and 2i + 1 through square i; top node
    // 2i + 1 meets 2i − 2, 2i − 1, 2i through square i − 1 and 2i, 2i + 3 through square i.
    std::vector<std::int32_t> bottom{2 * i - 2, 2 * i, 2 * i + 1, 2 * i + 2, 2 * i + 3};
    std::vector<std::int32_t> top{2 * i - 2, 2 * i - 1, 2 * i, 2 * i + 1, 2 * i + 3};
    if (i == 0) bottom = {0, 1, 2, 3}, top = {0, 1, 3};
    if (i == n - 1) bottom = {2 * i - 2, 2 * i, 2 * i + 1}, top = {2 * i - 2, 2 * i - 1, 2 * i, 2 * i + 1};
    for (const auto& [node, want] : {std::pair{2 * i, bottom}, std::pair{2 * i + 1, top}}) {
      const auto* row = topo.node_nodes.data() + topo.node_node_offset[static_cast<std::size_t>(node)];
      const auto* end = topo.node_nodes.data() + topo.node_node_offset[static_cast<std::size_t>(node) + 1];
      ASSERT_EQ(std::vector<std::int32_t>(row, end), want) << "node " << node;
    }
  }
}

TEST(Topology, RejectsAFacetSharedByThreeCells) {
  auto m = two_triangles();
  const std::int32_t t2[] = {0, 2, 1};
  m.cells[0].push_back(t2, 7);
  EXPECT_THROW(build_topology(m), InputError);
}

TEST(Mesh, FindsGroupsByNameAndNumberAndListsTheirNodes) {
  const auto m = two_triangles();
  ASSERT_TRUE(m.find_group("top"));
  EXPECT_EQ(m.group_nodes(*m.find_group("top")), (std::vector<std::int32_t>{2, 3}));
  EXPECT_EQ(m.find_group("1")->name, "bottom");
  EXPECT_EQ(m.find_group("7")->name, "domain");
  EXPECT_FALSE(m.find_group("wall"));
  EXPECT_FALSE(m.find_group("99"));
  EXPECT_FALSE(m.find_group("4294967297"));  // past int
  EXPECT_FALSE(m.find_group("99999999999999999999999"));
  const auto index = m.node_index_of_tag();
  EXPECT_EQ(index.at(30), 2);
  EXPECT_FALSE(index.contains(25));
}

TEST(Mesh, NodeTagsMayBeSparseAndLarge) {
  auto m = two_triangles();
  m.node_tags[1] = std::int64_t{1} << 62;  // MSH 4.1 allows size_t tags
  const auto index = m.node_index_of_tag();
  EXPECT_EQ(index.at(std::int64_t{1} << 62), 1);
  EXPECT_EQ(index.size(), m.n_nodes());
}

TEST(Mesh, MaxCellNodesTakesTheDensestBlockOfTheMeshDimension) {
  auto m = two_triangles();
  EXPECT_EQ(m.max_cell_nodes(), 3);  // the facets' lines do not count
  CellBlock p2{ElementType::Triangle, 2, {}, {}, {}};
  const std::int32_t t[] = {0, 1, 2, 0, 1, 2};
  p2.push_back(t, 7);
  m.cells.push_back(p2);
  EXPECT_EQ(m.max_cell_nodes(), 6);
  EXPECT_EQ(Mesh{}.max_cell_nodes(), 0);
}

}  // namespace
}  // namespace meshmorph
