// SPDX-License-Identifier: MIT
#include "meshmorph/mesh/node_order.h"

#include <algorithm>
#include <numeric>
#include <random>

#include <gtest/gtest.h>

#include "meshmorph/error.h"

namespace meshmorph {
namespace {

// An n × n grid of squares, each cut into two triangles, its nodes numbered by `number`
// (node (i, j) of the grid becomes node number[i + (n + 1) j]); the bottom side is a tagged
// facet group, and a nodal field holds each node's x + 10 y.
Mesh grid(int n, const std::vector<std::int32_t>& number) {
  const int side = n + 1;
  Mesh m;
  m.dim = 2;
  m.x.resize(2, side * side);
  m.node_tags.resize(static_cast<std::size_t>(side * side));
  Eigen::VectorXd field(side * side);
  for (int j = 0; j < side; ++j)
    for (int i = 0; i < side; ++i) {
      const std::int32_t v = number[static_cast<std::size_t>(i + side * j)];
      m.x.col(v) << i, j;
      m.node_tags[static_cast<std::size_t>(v)] = 1 + i + side * j;
      field[v] = i + 10.0 * j;
    }
  m.node_fields.emplace("height", field);
  CellBlock tris{ElementType::Triangle, 1, {}, {}, {}};
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const auto at = [&](int a, int b) { return number[static_cast<std::size_t>(a + side * b)]; };
      const std::int32_t lower[] = {at(i, j), at(i + 1, j), at(i + 1, j + 1)};
      const std::int32_t upper[] = {at(i, j), at(i + 1, j + 1), at(i, j + 1)};
      tris.push_back(lower, 1, i + n * j);
      tris.push_back(upper, 2, i + n * j);
    }
  m.cells.push_back(tris);
  CellBlock lines{ElementType::Line, 1, {}, {}, {}};
  for (int i = 0; i < n; ++i) {
    const std::int32_t l[] = {number[static_cast<std::size_t>(i)], number[static_cast<std::size_t>(i + 1)]};
    lines.push_back(l, 5);
  }
  m.facets.push_back(lines);
  m.groups.push_back(PhysicalGroup{1, 5, "bottom"});
  return m;
}

std::vector<std::int32_t> shuffled(std::size_t n, unsigned seed) {
  std::vector<std::int32_t> v(n);
  std::iota(v.begin(), v.end(), 0);
  std::shuffle(v.begin(), v.end(), std::mt19937(seed));
  return v;
}

// The largest difference of two node indices of one cell.
std::int32_t bandwidth(const Mesh& m) {
  std::int32_t w = 0;
  for (const CellBlock& b : m.cells)
    for (std::size_t c = 0; c < b.n_cells(); ++c) {
      const auto [lo, hi] = std::minmax_element(b.cell(c), b.cell(c) + b.n_nodes_per_cell());
      w = std::max(w, *hi - *lo);
    }
  return w;
}

TEST(NodeOrder, BringsTheNodesOfAShuffledGridBackToAGridsBandwidth) {
  const int n = 30;
  const Mesh mesh = grid(n, shuffled(static_cast<std::size_t>((n + 1) * (n + 1)), 7));
  ASSERT_GT(bandwidth(mesh), 10 * (n + 2));  // a generator's numbering: neighbours far apart
  const std::vector<std::int32_t> order = locality_order(build_topology(mesh));
  std::vector<std::int32_t> sorted = order;
  std::sort(sorted.begin(), sorted.end());
  std::vector<std::int32_t> all(mesh.n_nodes());
  std::iota(all.begin(), all.end(), 0);
  EXPECT_EQ(sorted, all);
  // Row by row the grid has bandwidth n + 2; Cuthill–McKee's diagonal fronts stay within
  // twice that.
  EXPECT_LE(bandwidth(renumber_nodes(mesh, order)), 2 * (n + 2));
  EXPECT_EQ(locality_order(build_topology(mesh)), order);  // deterministic
}

TEST(NodeOrder, RenumberingMovesCoordinatesTagsFieldsAndCellsTogether) {
  const int n = 6;
  const Mesh mesh = grid(n, shuffled(static_cast<std::size_t>((n + 1) * (n + 1)), 3));
  const std::vector<std::int32_t> order = locality_order(build_topology(mesh));
  const Mesh r = renumber_nodes(mesh, order);
  ASSERT_EQ(r.n_nodes(), mesh.n_nodes());
  for (std::size_t k = 0; k < r.n_nodes(); ++k) {
    EXPECT_EQ(r.x.col(static_cast<Eigen::Index>(k)), mesh.x.col(order[k]));
    EXPECT_EQ(r.node_tags[k], mesh.node_tags[static_cast<std::size_t>(order[k])]);
    EXPECT_EQ(r.node_fields.at("height")[static_cast<Eigen::Index>(k)], mesh.node_fields.at("height")[order[k]]);
  }
  // The same cells, each with its tags and its corners in their order, as coordinates; sorted
  // by their least node.
  const CellBlock &a = mesh.cells[0], &b = r.cells[0];
  ASSERT_EQ(b.n_cells(), a.n_cells());
  std::vector<bool> found(a.n_cells(), false);
  std::int32_t last_least = -1;
  for (std::size_t c = 0; c < b.n_cells(); ++c) {
    const std::int32_t least = *std::min_element(b.cell(c), b.cell(c) + 3);
    EXPECT_GE(least, last_least);
    last_least = least;
    // Entity tags number the squares, physical tags the triangle in it: together one cell.
    std::size_t same = a.n_cells();
    for (std::size_t e = 0; e < a.n_cells(); ++e)
      if (a.entity[e] == b.entity[c] && a.physical[e] == b.physical[c]) same = e;
    ASSERT_LT(same, a.n_cells());
    EXPECT_FALSE(found[same]);
    found[same] = true;
    for (int k = 0; k < 3; ++k) EXPECT_EQ(r.x.col(b.cell(c)[k]), mesh.x.col(a.cell(same)[k]));
  }
  const CellBlock &fa = mesh.facets[0], &fb = r.facets[0];
  ASSERT_EQ(fb.nodes.size(), fa.nodes.size());
  for (std::size_t k = 0; k < fa.nodes.size(); ++k) EXPECT_EQ(r.x.col(fb.nodes[k]), mesh.x.col(fa.nodes[k]));
  EXPECT_EQ(r.group_nodes(r.groups[0]).size(), static_cast<std::size_t>(n + 1));
}

TEST(NodeOrder, PlacesEveryPartOfADisconnectedMeshAndNodesOfNoCell) {
  // Two grids side by side, and one node that no cell holds.
  const int n = 4, side = n + 1;
  std::vector<std::int32_t> number(static_cast<std::size_t>(side * side));
  std::iota(number.begin(), number.end(), 0);
  Mesh a = grid(n, number), b = grid(n, number);
  Mesh m = a;
  m.node_fields.clear();
  m.node_tags.clear();
  m.x.resize(2, 2 * side * side + 1);
  m.x << a.x, (b.x.array() + 10.0).matrix(), Eigen::Vector2d(-5, -5);
  for (std::int32_t& v : b.cells[0].nodes) v += side * side;
  m.cells[0].nodes.insert(m.cells[0].nodes.end(), b.cells[0].nodes.begin(), b.cells[0].nodes.end());
  m.cells[0].physical.insert(m.cells[0].physical.end(), b.cells[0].physical.begin(), b.cells[0].physical.end());
  m.cells[0].entity.insert(m.cells[0].entity.end(), b.cells[0].entity.begin(), b.cells[0].entity.end());
  const std::vector<std::int32_t> order = locality_order(build_topology(m));
  std::vector<std::int32_t> sorted = order;
  std::sort(sorted.begin(), sorted.end());
  std::vector<std::int32_t> all(m.n_nodes());
  std::iota(all.begin(), all.end(), 0);
  EXPECT_EQ(sorted, all);
  EXPECT_LE(bandwidth(renumber_nodes(m, order)), 2 * (n + 2));  // the parts are not interleaved
}

TEST(NodeOrder, RefusesAnOrderThatIsNotAPermutation) {
  const int n = 2;
  std::vector<std::int32_t> number(9);
  std::iota(number.begin(), number.end(), 0);
  const Mesh m = grid(n, number);
  std::vector<std::int32_t> order = number;
  order[3] = 4;
  EXPECT_THROW(renumber_nodes(m, order), std::invalid_argument);
  order.pop_back();
  EXPECT_THROW(renumber_nodes(m, order), std::invalid_argument);
}

}  // namespace
}  // namespace meshmorph
