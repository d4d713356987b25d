// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <vector>

#include <Eigen/SparseCore>

#include "meshmorph/energy/dof_map.h"
#include "meshmorph/mesh/topology.h"

namespace meshmorph::detail {

/// Topology::node_nodes annotated with free-DOF counts: the column of a free DOF of node B
/// holds, for each neighbour A of B in sorted order, the free DOFs of A. `prefix[i]` is the
/// position within such a column of the first row of neighbour node_nodes[i].
struct NodePattern {
  std::vector<std::int32_t> prefix;     // per node_nodes entry
  std::vector<std::int32_t> row_count;  // per node: entries per column of its free DOFs
};

NodePattern build_node_pattern(const Topology& topology, const DofMap& dofs);

/// The column pointers of the reduced Hessian's CSC pattern (n_free × n_free): `outer`, n_free
/// + 1 entries. Throws std::invalid_argument when the pattern has 2³¹ entries or more.
void reduced_hessian_columns(const DofMap& dofs, const NodePattern& pattern, std::vector<int>& outer);
/// Its row indices, written to `inner` (outer[n_free] entries) column by column from the
/// topology: cheaper to make again than to keep, as each Hessian holds its own copy.
void reduced_hessian_rows(const Topology& topology, const DofMap& dofs, const int* outer, int* inner);

/// Greedy colouring of the cells of one block (global cell c = first_cell + local): a cell
/// takes the smallest colour unused by the earlier cells that share a node with it. Output:
/// cells sorted by colour then index (`order`) and the colour offsets into it (patch_cells
/// with one cell per patch).
void color_cells(const CellBlock& block, const Topology& topology, std::size_t first_cell,
                 std::vector<std::int32_t>& color_offset, std::vector<std::int32_t>& order);

/// Cells of one block in patches, and the patches coloured (global cell c = first_cell + local).
/// A patch is grown breadth-first through shared nodes from its lowest free cell up to
/// `patch_size` cells, so that the cells of a patch are neighbours and write to nearby Hessian
/// entries; a patch takes the smallest colour unused by the earlier patches that share a node
/// with it. Output: the cells patch by patch, patches sorted by colour then id (`order`), patch
/// p = order[patch_offset[p] .. [p + 1]), colour k = patches [color_offset[k] .. [k + 1]).
struct CellPatches {
  std::vector<std::int32_t> color_offset;
  std::vector<std::int32_t> patch_offset;
  std::vector<std::int32_t> order;
};

CellPatches patch_cells(const CellBlock& block, const Topology& topology, std::size_t first_cell, int patch_size);

/// Scatter map of one block: entry (c, a + n·b) is NodePattern::prefix of node a in the row
/// list of node b, i.e. the offset of a's rows in every column of b.
std::vector<std::int32_t> scatter_offsets(const CellBlock& block, const Topology& topology, const NodePattern& pattern);

}  // namespace meshmorph::detail
