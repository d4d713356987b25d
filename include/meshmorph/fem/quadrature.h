// SPDX-License-Identifier: MIT
#pragma once
#include <Eigen/Core>

#include "meshmorph/mesh/element_type.h"

namespace meshmorph {

/// A quadrature rule on a reference element (mesh reference domains: unit simplex,
/// [−1, 1]^d), exact for polynomials of total degree `degree` on simplices and of degree
/// `degree` in each variable on tensor cells. Weights are positive and sum to the
/// reference measure (reference_element.h: reference_measure).
struct QuadratureRule {
  ElementType type;
  int degree = 0;
  Eigen::MatrixXd points;   ///< dim × n_points
  Eigen::VectorXd weights;  ///< n_points

  int n_points() const { return static_cast<int>(weights.size()); }
};

/// The 1D rule of the products on tensor cells.
enum class QuadratureFamily {
  Gauss,    ///< Gauss–Legendre: n points exact to degree 2n − 1, all interior
  /// Gauss–Lobatto: n points exact to degree 2n − 3, the two end points included, so the
  /// products sample the corners, edges and faces of the cell (MFEM's -qt 1).
  Lobatto,
};

/// Shared rule of at least `degree`: Gauss–Legendre products on tensor cells (Gauss–Lobatto
/// products for `Lobatto`, which does not change the rules of simplices); on simplices
/// fully symmetric rules with positive weights and interior points for degrees 2–8 where
/// one is tabulated (src/fem/detail/simplex_rules.inc), otherwise collapsed Gauss–Jacobi
/// (Stroud conical) products; one point (the centroid) for degree ≤ 1. Prisms: the triangle's
/// rule times Gauss–Legendre in ζ; for `Lobatto`, the collapsed triangle ξ = s(1 − t), η = t
/// with Gauss–Lobatto points in s and Gauss–Lobatto–Jacobi points of weight 1 − t in t (the
/// points at t = 1 joined at the corner) times Gauss–Lobatto in ζ, m = (degree + 4)/2 points
/// each: exact to `degree`, the corners, edges and faces among the points, positive weights,
/// not symmetric. Pyramids: Gauss–Legendre × Gauss–Legendre × Gauss–Jacobi on the collapsed
/// cube (Duffy), exact to `degree` in the collapsed coordinates, always Gauss.
const QuadratureRule& quadrature_rule(ElementType type, int degree, QuadratureFamily family = QuadratureFamily::Gauss);

/// Degree used by default for mesh-quality integrals on an element of `order`: 1 for
/// linear simplices (A is constant: one point is exact), 2p for curved simplices and
/// 2p + 1 for tensor cells, which integrates |A|² exactly and the rational metrics of
/// DESIGN §2 to high accuracy on well-shaped elements.
int metric_quadrature_degree(ElementType type, int order);

}  // namespace meshmorph
