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
