// SPDX-License-Identifier: MIT
#include "meshmorph/parallel/local_mesh.h"

#include <algorithm>
#include <limits>

#include "meshmorph/error.h"

namespace meshmorph {
namespace {

constexpr int kNone = std::numeric_limits<int>::max();

// Calls f(block, cell, global cell index) for every cell of mesh.
template <class F>
void for_cells(const Mesh& mesh, F f) {
  std::size_t global = 0;
  for (std::size_t b = 0; b < mesh.cells.size(); ++b)
    for (std::size_t c = 0; c < mesh.cells[b].n_cells(); ++c) f(b, c, global++);
}

}  // namespace

std::vector<LocalMesh> split_mesh(const Mesh& mesh, const std::vector<int>& cell_rank, int n_ranks,
                                  const std::vector<std::uint8_t>& fixed) {
  const int d = mesh.dim;
  const std::size_t n = mesh.n_nodes();
  MESHMORPH_CHECK(cell_rank.size() == mesh.n_cells(), "split_mesh: one rank per cell");
  MESHMORPH_CHECK(fixed.size() == static_cast<std::size_t>(d) * n, "split_mesh: one fixed flag per DOF");
  std::vector<int> owner(n, kNone);
  for_cells(mesh, [&](std::size_t b, std::size_t c, std::size_t g) {
    const CellBlock& block = mesh.cells[b];
    for (int a = 0; a < block.n_nodes_per_cell(); ++a) {
      int& o = owner[static_cast<std::size_t>(block.cell(c)[a])];
      o = std::min(o, cell_rank[g]);
    }
  });
  // Global free numbers: rank by rank, nodes in order within a rank.
  std::vector<std::int32_t> global_free(fixed.size(), -1);
  std::vector<std::int32_t> first_free(static_cast<std::size_t>(n_ranks) + 1, 0);
  {
    std::vector<std::vector<std::int32_t>> owned(static_cast<std::size_t>(n_ranks));
    for (std::size_t i = 0; i < n; ++i)
      if (owner[i] != kNone) owned[static_cast<std::size_t>(owner[i])].push_back(static_cast<std::int32_t>(i));
    std::int32_t next = 0;
    for (int r = 0; r < n_ranks; ++r) {
      first_free[static_cast<std::size_t>(r)] = next;
      for (const std::int32_t i : owned[static_cast<std::size_t>(r)])
        for (int k = 0; k < d; ++k)
          if (!fixed[static_cast<std::size_t>(d * i + k)]) global_free[static_cast<std::size_t>(d * i + k)] = next++;
    }
    first_free[static_cast<std::size_t>(n_ranks)] = next;
  }

  std::vector<LocalMesh> parts(static_cast<std::size_t>(n_ranks));
  // The ranks that own a cell around each node: a cell is a ghost of rank r when one of its
  // nodes lies in an owned cell of r.
  std::vector<std::vector<int>> node_ranks(n);
  for_cells(mesh, [&](std::size_t b, std::size_t c, std::size_t g) {
    const CellBlock& block = mesh.cells[b];
    for (int a = 0; a < block.n_nodes_per_cell(); ++a) {
      std::vector<int>& r = node_ranks[static_cast<std::size_t>(block.cell(c)[a])];
      if (std::find(r.begin(), r.end(), cell_rank[g]) == r.end()) r.push_back(cell_rank[g]);
    }
  });
  std::vector<std::int32_t> local(n, -1);
  for (int r = 0; r < n_ranks; ++r) {
    LocalMesh& part = parts[static_cast<std::size_t>(r)];
    part.rank = r;
    part.mesh.dim = d;
    // Owned (0) and ghost (1) cells per block, and the nodes they hold.
    std::vector<std::uint8_t> role(mesh.n_cells(), 2);
    std::vector<std::uint8_t> in_part(n, 0);
    for_cells(mesh, [&](std::size_t b, std::size_t c, std::size_t g) {
      const CellBlock& block = mesh.cells[b];
      bool ghost = false;
      for (int a = 0; a < block.n_nodes_per_cell() && !ghost; ++a) {
        const std::vector<int>& around = node_ranks[static_cast<std::size_t>(block.cell(c)[a])];
        ghost = std::find(around.begin(), around.end(), r) != around.end();
      }
      role[g] = cell_rank[g] == r ? 0 : ghost ? 1 : 2;
      if (role[g] < 2)
        for (int a = 0; a < block.n_nodes_per_cell(); ++a) in_part[static_cast<std::size_t>(block.cell(c)[a])] = 1;
    });
    for (std::size_t i = 0; i < n; ++i)
      if (in_part[i] && owner[i] == r) part.global_node.push_back(static_cast<std::int64_t>(i));
    part.n_owned_nodes = part.global_node.size();
    for (std::size_t i = 0; i < n; ++i)
      if (in_part[i] && owner[i] != r) part.global_node.push_back(static_cast<std::int64_t>(i));
    const std::size_t m = part.global_node.size();
    part.mesh.x.resize(d, static_cast<Eigen::Index>(m));
    part.fixed.resize(static_cast<std::size_t>(d) * m);
    for (std::size_t j = 0; j < m; ++j) {
      const auto i = static_cast<std::size_t>(part.global_node[j]);
      local[i] = static_cast<std::int32_t>(j);
      part.mesh.x.col(static_cast<Eigen::Index>(j)) = mesh.x.col(static_cast<Eigen::Index>(i));
      for (int k = 0; k < d; ++k) {
        const std::size_t dof = static_cast<std::size_t>(d) * i + k;
        part.fixed[d * j + k] = fixed[dof];
        if (!fixed[dof]) part.global_free.push_back(global_free[dof]);
      }
    }
    part.first_owned_free = first_free[static_cast<std::size_t>(r)];
    part.n_owned_free = first_free[static_cast<std::size_t>(r) + 1] - part.first_owned_free;
    part.n_global_free = first_free[static_cast<std::size_t>(n_ranks)];
    for (const CellBlock& block : mesh.cells) {
      CellBlock empty;
      empty.type = block.type;
      empty.order = block.order;
      part.mesh.cells.push_back(empty);
      part.ghosts.push_back(empty);
    }
    std::vector<std::int32_t> cell;
    for_cells(mesh, [&](std::size_t b, std::size_t c, std::size_t g) {
      if (role[g] == 2) return;
      const CellBlock& block = mesh.cells[b];
      cell.resize(static_cast<std::size_t>(block.n_nodes_per_cell()));
      for (std::size_t a = 0; a < cell.size(); ++a) cell[a] = local[static_cast<std::size_t>(block.cell(c)[a])];
      const std::int32_t physical = block.physical.empty() ? 0 : block.physical[c];
      (role[g] == 0 ? part.mesh.cells[b] : part.ghosts[b]).push_back(cell.data(), physical);
    });
    for (const std::int64_t i : part.global_node) local[static_cast<std::size_t>(i)] = -1;
  }
  return parts;
}

}  // namespace meshmorph
