// SPDX-License-Identifier: MIT
#pragma once
#include <vector>

#include <Eigen/Core>

#include "meshmorph/mesh/element_type.h"

namespace meshmorph {

/// VTK cell type of a family as written by meshmorph: VTK_VERTEX 1 for points, the
/// arbitrary-order Lagrange types 68 (curve), 69 (triangle), 70 (quadrilateral),
/// 71 (tetrahedron), 72 (hexahedron), 73 (wedge: prisms) and 74 (pyramid) for every order.
int vtk_cell_type(ElementType type);

/// VTK's parametric coordinates of the nodes of a Lagrange cell of (type, order), in VTK's
/// node order (VTK ≥ 9.0, file version 2.2): corners as in the linear cell, then the nodes
/// inside each edge (VTK's edge order and direction), inside each face (triangles
/// recursive, quadrilaterals lexicographic) and inside the cell (recursive for simplices,
/// lexicographic for hexahedra). All families on [0,1]^d / the unit simplex; dim × n.
/// Prisms: VTK's wedge (corners (0,0,0) (1,0,0) (0,1,0) and the same at t = 1; the edges of
/// the base, of the top, then the vertical ones; the quadrilateral faces (0 1 4 3) (1 2 5 4)
/// (2 0 3 5)); orders 1–2. Pyramids: order 1, the base then the apex.
Eigen::MatrixXd vtk_lagrange_points(ElementType type, int order);

/// The node permutation between VTK and the internal (Gmsh) ordering, found by matching
/// vtk_lagrange_points with reference_element(type, order).nodes (tensor cells mapped from
/// [−1,1] to [0,1]; prisms: (u, v, w) → (u, v, (w + 1)/2)): vtk_nodes[i] =
/// gmsh_nodes[perm[i]]. The linear Lagrange wedge's and the pyramid's are the identity.
/// Cached; thread-safe.
const std::vector<int>& vtk_to_gmsh_permutation(ElementType type, int order);

/// The permutation of a cell of VTK type `vtk_type`: vtk_to_gmsh_permutation, except for the
/// classic VTK_WEDGE (13), whose base triangle (0, 1, 2) faces away from (3, 4, 5) where
/// Gmsh's and VTK's Lagrange wedge's face it (meshio#185; VTK 9.1's vtkCellSizeFilter gives a
/// Gmsh-ordered VTK_WEDGE a negative volume): (0 2 1 3 5 4); VTK_QUADRATIC_WEDGE (26), whose
/// corners are VTK_WEDGE's, the same with its 9 edge nodes; VTK_QUADRATIC_PYRAMID (27): 13
/// nodes onto the first 13 of Gmsh's 14-node pyramid. VTK_QUADRATIC_QUAD (23) and
/// VTK_QUADRATIC_HEXAHEDRON (25) take the first 8 and 20 entries of the complete quadratic
/// cell's permutation, which map them onto Gmsh's first 8 and 20 nodes.
const std::vector<int>& vtk_cell_permutation(int vtk_type, ElementType type, int order);

}  // namespace meshmorph
