// SPDX-License-Identifier: MIT
#pragma once
#include <Eigen/Core>

#include "meshmorph/mesh/element_type.h"

namespace meshmorph {

/// Verdict's scaled Jacobian of a linear cell (ecosystem.md §B.1), so that values compare
/// with ParaView's "Mesh Quality" filter. X holds the corners (dim × n_corners, Gmsh order,
/// which for linear cells is also Verdict's/VTK's). 1 on the ideal cell.
///   - triangle: 2A·(2/√3) / max over corners of the product of the two edge lengths
///     (equilateral = 1; range [−2/√3, 2/√3]);
///   - quadrilateral: min over the 4 corners of the cross product of the two edges leaving
///     the corner, divided by their lengths (range [−1, 1]);
///   - tetrahedron: 6V·√2 / max over corners of the product of the three edge lengths
///     (regular tet = 1);
///   - hexahedron: min over the 8 corners and the centre (principal axes) of the determinant
///     of the three unit edge (axis) vectors (range [−1, 1]);
///   - prism (wedge): Verdict's wedge_scaled_jacobian, min over the 6 corners of the
///     determinant of the unit edges (two along the triangle, one vertical) times 2/√3 (the
///     regular prism of equal edges = 1), on Gmsh's order, as ParaView ≥ 5.10 (VTK ≥ 9.2,
///     which reorders VTK's wedge for Verdict) shows it;
///   - pyramid: Verdict's pyramid_scaled_jacobian, the least tetrahedron scaled Jacobian of
///     (0 1 2 4), (0 2 3 4), (0 1 3 4), (1 2 3 4) times √2, 0 when ≤ 0, 2 − q above 1 (the
///     pyramid of equal edges = 1).
/// Signed: negative for inverted cells. In 2D the sign is taken w.r.t. +z (counter-clockwise
/// positive, as Verdict with a surface normal; without one Verdict reports |value| for a
/// mirrored triangle). A cell with an edge (or axis) of zero length gives 0; non-finite
/// coordinates give NaN. Throws std::invalid_argument for a non-cell family.
double scaled_jacobian_linear(ElementType type, const Eigen::MatrixXd& X);

/// The scaled Jacobian, as above, of the affine cell whose Jacobian is A (d × d, on the
/// mesh reference element: unit simplex or [−1, 1]^d) — the cell tangent to a curved cell at
/// a point. Simplices: the Verdict formula on the edges of A's simplex; tensor cells:
/// det A / Π|A eₖ| (every corner of a parallelogram/parallelepiped agrees); prisms: that
/// times 2/√3, the wedge formula at a corner.
double scaled_jacobian_at(ElementType type, const Eigen::MatrixXd& A);

/// Scaled Jacobian of a cell of any order (X: dim × n_nodes, Gmsh order). Order 1: Verdict's
/// value (scaled_jacobian_linear). Order ≥ 2: the minimum over validity_samples(type, order)
/// of scaled_jacobian_at(A) (Gmsh's sampled minSJ, with simplices scaled so the
/// equilateral/regular cell gives 1, as for linear cells).
double scaled_jacobian(ElementType type, int order, const Eigen::MatrixXd& X);

}  // namespace meshmorph
