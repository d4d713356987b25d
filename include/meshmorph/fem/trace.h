// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <vector>

#include "meshmorph/mesh/topology.h"

namespace meshmorph {

/// Nodes of facet `local` of a cell, in the facet element's own ordering: the restriction
/// (trace) of the cell's nodes to that facet.
std::vector<std::int32_t> facet_nodes(const CellBlock& block, std::size_t cell, int local);

/// Sorted nodes of every order on the boundary facets of the mesh.
std::vector<std::int32_t> boundary_nodes(const Mesh& mesh, const Topology& topology);

}  // namespace meshmorph
