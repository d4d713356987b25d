// SPDX-License-Identifier: MIT
#pragma once
#include <vector>

#include <Eigen/Core>

#include "meshmorph/mesh/element_type.h"

namespace meshmorph {

/// VTK cell type of a family as written by meshmorph: VTK_VERTEX 1 for points, the
/// arbitrary-order Lagrange types 68 (curve), 69 (triangle), 70 (quadrilateral),
/// 71 (tetrahedron) and 72 (hexahedron) for every order.
int vtk_cell_type(ElementType type);

/// VTK's parametric coordinates of the nodes of a Lagrange cell of (type, order), in VTK's
/// node order (VTK ≥ 9.0, file version 2.2): corners as in the linear cell, then the nodes
/// inside each edge (VTK's edge order and direction), inside each face (triangles
/// recursive, quadrilaterals lexicographic) and inside the cell (recursive for simplices,
/// lexicographic for hexahedra). All families on [0,1]^d / the unit simplex; dim × n.
Eigen::MatrixXd vtk_lagrange_points(ElementType type, int order);

/// The node permutation between VTK and the internal (Gmsh) ordering, found by matching
/// vtk_lagrange_points with reference_element(type, order).nodes (tensor cells mapped from
/// [−1,1] to [0,1]): vtk_nodes[i] = gmsh_nodes[perm[i]]. Cached; thread-safe.
const std::vector<int>& vtk_to_gmsh_permutation(ElementType type, int order);

}  // namespace meshmorph
