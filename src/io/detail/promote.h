// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "meshmorph/mesh/mesh.h"

namespace meshmorph::detail {

/// Node count of the incomplete (serendipity) cell that is read as the complete quadratic
/// cell of `type`: 8 (quadrilateral), 20 (hexahedron), 15 (prism), 13 (pyramid); 0 for the
/// other families. The incomplete cell's nodes are the first ones of the complete cell's in
/// Gmsh's order; the complete cell's other nodes are the centres of its quadrilateral faces
/// and, in a hexahedron, of the cell.
int incomplete_nodes_of(ElementType type);

/// Completes the cells read as incomplete ones, whose missing nodes are −1 in their lists,
/// by adding nodes to `xyz` (3 per node), `tags` (the next free tags) and every field: a
/// quadrilateral face's centre where the 8-node serendipity quadrilateral puts it,
/// −¼ Σ corners + ½ Σ mid-edge nodes, one node per face whatever cells and facets hold it
/// (a complete cell's own face centre is kept); a hexahedron's centre where the 20-node one
/// puts it, −¼ Σ corners + ¼ Σ edge nodes. Field values take the same weights. These are
/// the values of the serendipity cell's map at those points (Gmsh's bases of types 16-19),
/// and its space lies in the complete cell's, so the complete cell is the same map.
/// Returns a note for the user ("read 48 15-node prisms as 18-node prisms"), empty when
/// no cell was promoted.
std::string promote_incomplete(std::vector<CellBlock>& blocks, std::vector<double>& xyz, std::vector<std::int64_t>& tags,
                               std::map<std::string, std::vector<double>, std::less<>>& fields);

}  // namespace meshmorph::detail
