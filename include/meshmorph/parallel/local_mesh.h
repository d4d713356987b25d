// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <vector>

#include "meshmorph/mesh/mesh.h"

namespace meshmorph {

/// One rank's part of a mesh (DESIGN §5): the cells it owns, one layer of ghost cells (the
/// cells of other ranks that share a node with an owned cell), and the nodes of both.
struct LocalMesh {
  int rank = 0;
  /// The owned cells on the local nodes, in the global mesh's blocks (every block kept, some
  /// perhaps empty); x holds the local nodes' coordinates. No facets and no groups.
  Mesh mesh;
  /// The ghost cells on the local nodes, block by block as mesh.cells.
  std::vector<CellBlock> ghosts;
  /// Global index of each local node: the nodes [0, n_owned_nodes) are the rank's own, in
  /// increasing global index, the others follow in increasing global index.
  std::vector<std::int64_t> global_node;
  std::size_t n_owned_nodes = 0;
  /// Fixed flag per local DOF (dim·node + k), as in the global mask.
  std::vector<std::uint8_t> fixed;
  /// Global number of each local free DOF, in DofMap::from_mask(dim, fixed) order. The free
  /// DOFs are numbered rank by rank, in each rank its owned nodes in order: the rank's own
  /// come first locally and are first_owned_free, first_owned_free + 1, …
  std::vector<std::int32_t> global_free;
  std::int32_t n_owned_free = 0;
  std::int32_t first_owned_free = 0;
  std::int32_t n_global_free = 0;
};

/// Splits `mesh` into the local meshes of `n_ranks` ranks: cell c (global order, blocks
/// concatenated) is owned by cell_rank[c]; a node by the lowest rank owning a cell that holds
/// it (nodes of no cell by none). `fixed` holds one flag per DOF of mesh. The same input
/// gives the same parts.
std::vector<LocalMesh> split_mesh(const Mesh& mesh, const std::vector<int>& cell_rank, int n_ranks,
                                  const std::vector<std::uint8_t>& fixed);

}  // namespace meshmorph
