// SPDX-License-Identifier: MIT
#include "meshmorph/parallel/local_mesh.h"

#include <algorithm>
#include <map>
#include <set>
#include <vector>

#include <gtest/gtest.h>

#include "meshmorph/io/mesh_io.h"

namespace meshmorph {
namespace {

using Cell = std::vector<std::int64_t>;  // a cell by its global nodes

std::vector<Cell> global_cells(const Mesh& mesh) {
  std::vector<Cell> cells;
  for (const CellBlock& b : mesh.cells)
    for (std::size_t c = 0; c < b.n_cells(); ++c) cells.emplace_back(b.cell(c), b.cell(c) + b.n_nodes_per_cell());
  return cells;
}

std::set<Cell> part_cells(const LocalMesh& part, const std::vector<CellBlock>& blocks) {
  std::set<Cell> cells;
  for (const CellBlock& b : blocks)
    for (std::size_t c = 0; c < b.n_cells(); ++c) {
      Cell cell;
      for (int a = 0; a < b.n_nodes_per_cell(); ++a) cell.push_back(part.global_node[static_cast<std::size_t>(b.cell(c)[a])]);
      cells.insert(cell);
    }
  return cells;
}

// The annulus in three parts by the x of the cells' first node, every fifth node fixed: each
// cell owned once, each node owned once, one layer of ghost cells, the free DOFs numbered
// rank by rank with the same number wherever a node is held.
TEST(SplitMesh, OwnsEachCellAndNodeOnceWithOneGhostLayer) {
  const Mesh mesh = read_mesh(MESHMORPH_TEST_DATA "/annulus_coarse.msh");
  const int n_ranks = 3, d = mesh.dim;
  const std::vector<Cell> cells = global_cells(mesh);
  std::vector<int> cell_rank;
  const double lo = mesh.x.row(0).minCoeff(), hi = mesh.x.row(0).maxCoeff();
  for (const Cell& c : cells)
    cell_rank.push_back(std::min(n_ranks - 1, static_cast<int>(n_ranks * (mesh.x(0, c[0]) - lo) / (hi - lo))));
  std::vector<std::uint8_t> fixed(static_cast<std::size_t>(d) * mesh.n_nodes(), 0);
  for (std::size_t i = 0; i < mesh.n_nodes(); i += 5) std::fill_n(fixed.begin() + d * i, d, 1);

  const std::vector<LocalMesh> parts = split_mesh(mesh, cell_rank, n_ranks, fixed);
  ASSERT_EQ(parts.size(), 3u);
  std::vector<int> node_owners(mesh.n_nodes(), 0);
  std::map<std::int64_t, std::int32_t> free_number;  // global DOF → number, from its owner
  std::int32_t next_free = 0;
  std::size_t owned_cells = 0;
  for (int r = 0; r < n_ranks; ++r) {
    const LocalMesh& part = parts[static_cast<std::size_t>(r)];
    const std::set<Cell> owned = part_cells(part, part.mesh.cells), ghosts = part_cells(part, part.ghosts);
    std::set<std::int64_t> owned_nodes;
    for (std::size_t c = 0; c < cells.size(); ++c) {
      const bool mine = cell_rank[c] == r;
      EXPECT_EQ(owned.count(cells[c]), mine ? 1u : 0u);
      if (mine) owned_nodes.insert(cells[c].begin(), cells[c].end());
    }
    owned_cells += owned.size();
    for (std::size_t c = 0; c < cells.size(); ++c) {
      const bool touches = std::any_of(cells[c].begin(), cells[c].end(), [&](std::int64_t i) { return owned_nodes.count(i) > 0; });
      EXPECT_EQ(ghosts.count(cells[c]), cell_rank[c] != r && touches ? 1u : 0u) << "rank " << r << " cell " << c;
    }
    EXPECT_TRUE(std::is_sorted(part.global_node.begin(), part.global_node.begin() + part.n_owned_nodes));
    EXPECT_EQ(part.first_owned_free, next_free);
    std::size_t k_free = 0;
    for (std::size_t j = 0; j < part.global_node.size(); ++j) {
      const std::int64_t i = part.global_node[j];
      EXPECT_EQ(part.mesh.x.col(static_cast<Eigen::Index>(j)), mesh.x.col(i));
      if (j < part.n_owned_nodes) ++node_owners[static_cast<std::size_t>(i)];
      for (int k = 0; k < d; ++k) {
        ASSERT_EQ(part.fixed[d * j + k], fixed[d * i + k]);
        if (fixed[d * i + k]) continue;
        const std::int32_t number = part.global_free.at(k_free++);
        if (j >= part.n_owned_nodes) continue;
        EXPECT_EQ(number, next_free++);
        free_number[d * i + k] = number;
      }
    }
    EXPECT_EQ(k_free, part.global_free.size());
    EXPECT_EQ(part.n_owned_free, next_free - part.first_owned_free);
  }
  EXPECT_EQ(owned_cells, cells.size());
  for (std::size_t i = 0; i < mesh.n_nodes(); ++i) EXPECT_EQ(node_owners[i], 1) << "node " << i;
  // A ghost node carries its owner's number.
  for (const LocalMesh& part : parts) {
    EXPECT_EQ(part.n_global_free, next_free);
    std::size_t k_free = 0;
    for (std::size_t j = 0; j < part.global_node.size(); ++j)
      for (int k = 0; k < d; ++k)
        if (!part.fixed[d * j + k]) {
          EXPECT_EQ(part.global_free[k_free++], free_number.at(d * part.global_node[j] + k));
        }
  }
}

}  // namespace
}  // namespace meshmorph
