// SPDX-License-Identifier: MIT
#include "energy/detail/pattern.h"

#include <algorithm>
#include <limits>

#include "meshmorph/error.h"

namespace meshmorph::detail {

NodePattern build_node_pattern(const Topology& topology, const DofMap& dofs) {
  const std::size_t n_nodes = dofs.n_nodes();
  NodePattern p;
  p.prefix.resize(topology.node_nodes.size());
  p.row_count.assign(n_nodes, 0);
  const auto n = static_cast<std::int64_t>(n_nodes);
#pragma omp parallel for schedule(static)
  for (std::int64_t b = 0; b < n; ++b) {
    std::int64_t count = 0;
    for (auto i = topology.node_node_offset[static_cast<std::size_t>(b)];
         i < topology.node_node_offset[static_cast<std::size_t>(b) + 1]; ++i) {
      const auto a = static_cast<std::size_t>(topology.node_nodes[static_cast<std::size_t>(i)]);
      p.prefix[static_cast<std::size_t>(i)] = static_cast<std::int32_t>(count);
      count += dofs.first(a + 1) - dofs.first(a);
    }
    p.row_count[static_cast<std::size_t>(b)] = static_cast<std::int32_t>(count);
  }
  return p;
}

void reduced_hessian_columns(const DofMap& dofs, const NodePattern& pattern, std::vector<int>& outer) {
  const std::size_t n_nodes = dofs.n_nodes();
  std::vector<std::int64_t> colptr(dofs.n_free() + 1, 0);
  for (std::size_t b = 0; b < n_nodes; ++b)
    for (std::int32_t col = dofs.first(b); col < dofs.first(b + 1); ++col)
      colptr[static_cast<std::size_t>(col) + 1] = colptr[static_cast<std::size_t>(col)] + pattern.row_count[b];
  MESHMORPH_CHECK(colptr.back() < std::numeric_limits<int>::max(),
                  "EnergyAssembler: the Hessian has too many entries for 32-bit indices");
  outer.assign(colptr.begin(), colptr.end());
}

void reduced_hessian_rows(const Topology& topology, const DofMap& dofs, const int* outer, int* inner) {
  const auto n = static_cast<std::int64_t>(dofs.n_nodes());
#pragma omp parallel for schedule(static)
  for (std::int64_t b = 0; b < n; ++b) {
    const auto ub = static_cast<std::size_t>(b);
    for (std::int32_t col = dofs.first(ub); col < dofs.first(ub + 1); ++col) {
      int* rows = inner + outer[col];
      for (auto i = topology.node_node_offset[ub]; i < topology.node_node_offset[ub + 1]; ++i) {
        const auto a = static_cast<std::size_t>(topology.node_nodes[static_cast<std::size_t>(i)]);
        for (std::int32_t r = dofs.first(a); r < dofs.first(a + 1); ++r) *rows++ = r;
      }
    }
  }
}

CellPatches patch_cells(const CellBlock& block, const Topology& topology, std::size_t first_cell, int patch_size) {
  const std::size_t n_cells = block.n_cells();
  const int n = block.n_nodes_per_cell();
  // Calls f(g) for every cell g (local index) of the block that shares a node with cell c.
  auto for_neighbours = [&](std::size_t c, auto&& f) {
    const std::int32_t* nodes = block.cell(c);
    for (int a = 0; a < n; ++a) {
      const auto v = static_cast<std::size_t>(nodes[a]);
      for (const std::int32_t cell : topology.cells_of(v)) {
        const auto g = static_cast<std::size_t>(cell);
        if (g >= first_cell && g < first_cell + n_cells) f(g - first_cell);
      }
    }
  };
  std::vector<std::int32_t> patch(n_cells, -1);
  std::vector<std::int32_t> members;  // cells patch by patch, in patch id order
  std::vector<std::int32_t> member_offset{0};
  members.reserve(n_cells);
  for (std::size_t seed = 0; seed < n_cells; ++seed) {
    if (patch[seed] >= 0) continue;
    const auto p = static_cast<std::int32_t>(member_offset.size() - 1);
    const std::size_t begin = members.size();
    patch[seed] = p;
    members.push_back(static_cast<std::int32_t>(seed));
    for (std::size_t next = begin; next < members.size() && members.size() - begin < static_cast<std::size_t>(patch_size); ++next)
      for_neighbours(static_cast<std::size_t>(members[next]), [&](std::size_t g) {
        if (patch[g] >= 0 || members.size() - begin >= static_cast<std::size_t>(patch_size)) return;
        patch[g] = p;
        members.push_back(static_cast<std::int32_t>(g));
      });
    member_offset.push_back(static_cast<std::int32_t>(members.size()));
  }
  const std::size_t n_patches = member_offset.size() - 1;
  std::vector<std::int32_t> color(n_patches, -1);
  std::vector<std::int64_t> seen;  // seen[k] == p: colour k is taken by a neighbour of patch p
  int n_colors = 0;
  for (std::size_t p = 0; p < n_patches; ++p) {
    for (auto i = member_offset[p]; i < member_offset[p + 1]; ++i)
      for_neighbours(static_cast<std::size_t>(members[static_cast<std::size_t>(i)]), [&](std::size_t g) {
        const std::int32_t k = color[static_cast<std::size_t>(patch[g])];
        if (k >= 0) seen[static_cast<std::size_t>(k)] = static_cast<std::int64_t>(p);
      });
    int k = 0;
    while (k < n_colors && seen[static_cast<std::size_t>(k)] == static_cast<std::int64_t>(p)) ++k;
    if (k == n_colors) {
      ++n_colors;
      seen.push_back(-1);
    }
    color[p] = k;
  }
  CellPatches out;
  out.color_offset.assign(static_cast<std::size_t>(n_colors) + 1, 0);
  for (std::int32_t k : color) ++out.color_offset[static_cast<std::size_t>(k) + 1];
  for (std::size_t k = 0; k < static_cast<std::size_t>(n_colors); ++k) out.color_offset[k + 1] += out.color_offset[k];
  std::vector<std::int32_t> by_color(n_patches);
  std::vector<std::int32_t> fill(out.color_offset.begin(), out.color_offset.end() - 1);
  for (std::size_t p = 0; p < n_patches; ++p)
    by_color[static_cast<std::size_t>(fill[static_cast<std::size_t>(color[p])]++)] = static_cast<std::int32_t>(p);
  out.patch_offset.reserve(n_patches + 1);
  out.patch_offset.push_back(0);
  out.order.reserve(n_cells);
  for (std::int32_t p : by_color) {
    const auto up = static_cast<std::size_t>(p);
    out.order.insert(out.order.end(), members.begin() + member_offset[up], members.begin() + member_offset[up + 1]);
    out.patch_offset.push_back(static_cast<std::int32_t>(out.order.size()));
  }
  return out;
}

void color_cells(const CellBlock& block, const Topology& topology, std::size_t first_cell,
                 std::vector<std::int32_t>& color_offset, std::vector<std::int32_t>& order) {
  CellPatches single = patch_cells(block, topology, first_cell, 1);  // one cell per patch
  color_offset = std::move(single.color_offset);
  order = std::move(single.order);
}

std::vector<std::int32_t> scatter_offsets(const CellBlock& block, const Topology& topology, const NodePattern& pattern) {
  const int n = block.n_nodes_per_cell();
  const auto nn = static_cast<std::size_t>(n) * static_cast<std::size_t>(n);
  std::vector<std::int32_t> offsets(block.n_cells() * nn);
  const auto n_cells = static_cast<std::int64_t>(block.n_cells());
  bool missing = false;
#pragma omp parallel for schedule(static) reduction(|| : missing)
  for (std::int64_t c = 0; c < n_cells; ++c) {
    const std::int32_t* nodes = block.cell(static_cast<std::size_t>(c));
    std::int32_t* out = offsets.data() + static_cast<std::size_t>(c) * nn;
    for (int b = 0; b < n; ++b) {
      const auto vb = static_cast<std::size_t>(nodes[b]);
      const auto row_begin = topology.node_nodes.begin() + topology.node_node_offset[vb];
      const auto row_end = topology.node_nodes.begin() + topology.node_node_offset[vb + 1];
      for (int a = 0; a < n; ++a) {
        const auto it = std::lower_bound(row_begin, row_end, nodes[a]);
        if (it == row_end || *it != nodes[a]) {
          missing = true;
          continue;
        }
        out[a + n * b] = pattern.prefix[static_cast<std::size_t>(it - topology.node_nodes.begin())];
      }
    }
  }
  MESHMORPH_CHECK(!missing, "EnergyAssembler: Topology::node_nodes lacks a pair of nodes that share a cell");
  return offsets;
}

}  // namespace meshmorph::detail
