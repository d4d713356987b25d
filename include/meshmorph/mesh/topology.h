// SPDX-License-Identifier: MIT
#pragma once
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "meshmorph/mesh/mesh.h"

namespace meshmorph {

/// Local corner indices of the facets of a cell family, ordered so that the facet's
/// normal (right-hand rule) points out of the reference cell. Line facets are (a, b)
/// with the cell on the left. Gmsh corner numbering.
std::span<const std::vector<int>> corner_facets(ElementType t);
/// Local corner pairs of the edges of a cell family (Gmsh's edge order and direction).
std::span<const std::array<int, 2>> corner_edges(ElementType t);
/// Family of facet `f` of a cell family (Line, Triangle or Quadrilateral).
ElementType facet_type(ElementType t, int f);

/// A cell by global index (blocks of Mesh::cells concatenated) and a local facet of it.
struct CellFacet {
  std::int32_t cell = -1;
  std::int32_t local = -1;
};

/// Topology derived from the corner vertices of the cells of a mesh; built once per mesh.
struct Topology {
  std::vector<std::size_t> block_offset;  ///< global index of the first cell of each block (+ total)
  std::vector<std::array<std::int32_t, 2>> edges;  ///< unique edges as corner-node pairs (a < b)
  /// Unique facets: the two cells sharing it, or {cell, {-1,-1}} on the boundary.
  std::vector<std::array<CellFacet, 2>> facets;
  std::vector<std::int32_t> boundary_facets;  ///< indices into `facets` with one cell
  std::vector<std::int32_t> boundary_corners; ///< sorted corner nodes on boundary facets
  /// node → cells (CSR): cells of node i are node_cells[node_cell_offset[i] .. [i+1]).
  std::vector<std::int64_t> node_cell_offset;
  std::vector<std::int32_t> node_cells;
  /// node → nodes sharing a cell with it, itself included, sorted (CSR; the Hessian pattern).
  std::vector<std::int64_t> node_node_offset;
  std::vector<std::int32_t> node_nodes;
  /// cell → the cell across each local facet, -1 on the boundary (n_facets per cell, CSR).
  std::vector<std::int64_t> cell_neighbor_offset;
  std::vector<std::int32_t> cell_neighbors;

  /// (block, cell within block) of a global cell index.
  std::pair<std::size_t, std::size_t> locate(std::int32_t cell) const;
  /// The cells (global indices) that hold node i.
  std::span<const std::int32_t> cells_of(std::size_t i) const {
    return {node_cells.data() + node_cell_offset[i], node_cells.data() + node_cell_offset[i + 1]};
  }
};

/// What build_topology builds: all of it, or the facets alone (block_offset, facets,
/// boundary_facets, boundary_corners, cell neighbours) for walks from cell to cell.
enum class TopologyParts { All, Facets };

/// Builds the topology of the cells of `mesh`. Throws InputError if a facet is shared by
/// more than two cells (a non-manifold mesh).
Topology build_topology(const Mesh& mesh, TopologyParts parts = TopologyParts::All);

}  // namespace meshmorph
