// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "meshmorph/mesh/mesh.h"
#include "meshmorph/mesh/topology.h"

namespace meshmorph {

/// A numbering of the nodes that keeps the nodes of a cell close together: reverse
/// Cuthill–McKee over the graph of nodes that share a cell (the topology's node → nodes; a
/// node's degree is the number of cells around it), each connected part started from a node
/// far from the others (the last one reached by a breadth-first search from any of its
/// nodes). `order[k]` is the node of the topology's mesh that becomes node k. Mesh generators
/// number nodes by geometric entity and by insertion, so the neighbours of a node lie all
/// over the coordinate and solution vectors; in this order the sparse products and the
/// assembly read them from nearby memory. Deterministic: the same mesh gives the same order.
std::vector<std::int32_t> locality_order(const Topology& topology);

/// `mesh` with its nodes renumbered: node k of the result is node `order[k]` of `mesh`
/// (coordinates, tags and nodal fields moved, cells and facets renumbered), and the cells of
/// each block sorted by their least new node index, so that consecutive cells share nodes.
/// `order` must be a permutation of the nodes.
Mesh renumber_nodes(const Mesh& mesh, std::span<const std::int32_t> order);

}  // namespace meshmorph
