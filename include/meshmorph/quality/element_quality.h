// SPDX-License-Identifier: MIT
#pragma once
#include <Eigen/Core>

#include "meshmorph/mesh/element_type.h"

namespace meshmorph {

/// The target W of an element-quality measurement (DESIGN §2).
enum class QualityTarget {
  Input,  ///< W = the input element's Jacobian at each point: relative quality, 1 = undistorted
  Ideal,  ///< W = ideal_jacobian(type): absolute shape quality, 1 = regular simplex / square / cube / prism / pyramid of equal edges
};

/// The ideal element's Jacobian on the mesh reference element (d × d): the map from the
/// unit reference simplex to the regular simplex of unit edge (triangle: columns (1, 0),
/// (½, √3/2); tetrahedron: (1, 0, 0), (½, √3/2, 0), (½, √3/6, √(2/3))), and I for
/// quadrilaterals and hexahedra ([−1, 1]^d is already a square/cube; η₀ ignores the size).
Eigen::MatrixXd ideal_jacobian(ElementType type);

/// Element distortion η_e = √(∫ η₀(T)² dΩ / ∫ dΩ) (paper 000, eq. 9), T = A W⁻¹, integrated
/// over the target element: dΩ = |det W| w_q at the points of shape_table(type, order,
/// metric_quadrature_degree(type, order)). X: dim × n_nodes of the current cell (Gmsh order);
/// X_input: the same cell in the input mesh, or nullptr for the Ideal target. ≥ 1; +∞ when
/// det A ≤ 0 at a quadrature point (or det W ≤ 0: an inverted input element cannot serve
/// as a target).
double element_distortion(ElementType type, int order, const Eigen::MatrixXd& X, const Eigen::MatrixXd* X_input);

/// Element quality q_e = 1/η_e ∈ [0, 1] (paper 000, §5; DESIGN §3.3): 1 for the target
/// shape (any similarity of the input for the Input target, of the ideal element for the
/// Ideal target), 0 for an inverted cell (min_jacobian_det over validity_samples ≤ 0) and for
/// non-finite coordinates.
double element_quality(ElementType type, int order, const Eigen::MatrixXd& X, const Eigen::MatrixXd* X_input);

}  // namespace meshmorph
