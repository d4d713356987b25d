// SPDX-License-Identifier: MIT
#pragma once
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "meshmorph/mesh/element_type.h"

namespace meshmorph {

/// A family and order, as the CGNS and Exodus II element types name them.
using TypeOrder = std::pair<ElementType, int>;

/// CGNS ElementType_t of (type, order): NODE, BAR_2…5, TRI_3/6/10/15, QUAD_4/9/16/25,
/// TETRA_4/10/20/35, HEXA_8/27/64, PENTA_6/18/40/75, PYRA_5/14; 0 (ElementTypeNull) when
/// CGNS has no complete element of that order.
int cgns_element_type(ElementType type, int order);
/// The (type, order) of a CGNS ElementType_t, or empty (MIXED, NGON_n, serendipity types…).
std::optional<TypeOrder> cgns_type_order(int cgns_type);

/// The node positions of a CGNS element of (type, order) in the internal reference cell
/// (reference_element's coordinates), in CGNS's node order (SIDS: corners, the nodes inside
/// each edge — base edges, then edges rising from the base, then top edges — inside each
/// face, inside the cell; triangles and tetrahedra recursively, one quadrilateral face's
/// inner nodes corner by corner). Order 4 tetrahedra and prisms follow Gmsh's CGNS
/// converter. dim × n.
Eigen::MatrixXd cgns_reference_points(ElementType type, int order);

/// cgns_nodes[i] = gmsh_nodes[perm[i]] for a cell of (type, order); cached, thread-safe.
const std::vector<int>& cgns_to_gmsh_permutation(ElementType type, int order);

/// Exodus II element type name of (type, order), as written: SPHERE (points), BAR2/BAR3,
/// TRI3/TRI6, QUAD4/QUAD9, TETRA4/TETRA10, HEX8/HEX27, WEDGE6/WEDGE18, PYRAMID5/PYRAMID14;
/// empty when Exodus has no complete element of that order (order 3 and 4).
std::string exodus_element_name(ElementType type, int order);
/// The (type, order) of an Exodus element name with `nodes` nodes per element (names in
/// any case, with or without the node count: "tetra", "TET10", "HEX27", "wedge"…), or
/// empty (serendipity elements such as HEX20, shells, …).
std::optional<TypeOrder> exodus_type_order(std::string_view name, int nodes);

/// exodus_nodes[i] = gmsh_nodes[perm[i]]: CGNS's order up to order 2, except HEX27, whose
/// 21st node is the centre and the face centres follow as -z, +z, -x, +x, -y, +y.
const std::vector<int>& exodus_to_gmsh_permutation(ElementType type, int order);

/// The Exodus II sides of a cell family (side s is entry s − 1): their corners as
/// internal (Gmsh) corner indices, which Exodus numbers alike. Triangles and
/// quadrilaterals: edges 1–2, 2–3, …; tetrahedra (1 2 4) (2 3 4) (1 4 3) (1 3 2);
/// hexahedra (1 2 6 5) (2 3 7 6) (3 4 8 7) (1 5 8 4) (1 4 3 2) (5 6 7 8); wedges (1 2 5 4)
/// (2 3 6 5) (1 4 6 3) (1 3 2) (4 5 6); pyramids (1 2 5) (2 3 5) (3 4 5) (1 5 4) (1 4 3 2)
/// (1-based here as in the Exodus manual).
const std::vector<std::vector<int>>& exodus_sides(ElementType type);

}  // namespace meshmorph
