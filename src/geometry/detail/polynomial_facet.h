// SPDX-License-Identifier: MIT
#pragma once
#include <array>
#include <limits>

#include <Eigen/Core>

#include "meshmorph/fem/lagrange_basis.h"

namespace meshmorph::detail {

// Fixed capacities, so that the closest-point iterations never touch the heap: d ≤ 3,
// reference dimension m ≤ 2, n ≤ 25 nodes (quadrilaterals of order 4).
using FacetVec = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 3, 1>;                     // x ∈ ℝ^d
using FacetParam = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 2, 1>;                   // u ∈ ℝ^m
using FacetTangents = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 3, 2>;   // d × m
using FacetCurvature = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 3, 4>;  // d × m²
using FacetForm = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 2, 2>;       // m × m
using FacetCoeffs = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 3, 25>;    // d × n

/// The unit normal of tangents T (d × (d − 1)) by the right-hand rule (outward_normal).
template <class Tangents>
FacetVec unit_normal(const Tangents& T) {
  FacetVec n(T.rows());
  if (T.rows() == 2) {
    n << T(1, 0), -T(0, 0);  // the cell is left of a line facet
  } else {
    n << T(1, 0) * T(2, 1) - T(2, 0) * T(1, 1), T(2, 0) * T(0, 1) - T(0, 0) * T(2, 1), T(0, 0) * T(1, 1) - T(1, 0) * T(0, 1);
  }
  return n.normalized();
}

/// A facet's map at u: φ, T = ∂φ/∂u (d × m) and S = ∂²φ/∂u_k∂u_l (column k·m + l, d × m²).
struct FacetPoint {
  ElementType type = ElementType::Line;
  FacetParam u;
  FacetVec p;
  FacetTangents T;
  FacetCurvature S;
};

/// The closest point of a facet to x, |φ(u) − x|², and whether it lies on the rim of S.
struct FacetHit {
  double dist2 = std::numeric_limits<double>::infinity();
  FacetPoint at;
  bool rim = false;
};

/// What the facets of one (type, order) share: the monomials of the space LagrangeBasis
/// spans, the changes of basis from Lagrange nodes to monomial and Bézier coefficients, the
/// Newton start samples.
struct FacetShape;

/// One Lagrange facet of a facet surface (geometry/facet_surface.h): a line, triangle or
/// quadrilateral of order 1–4 in ℝ^d, its map φ(u) = x₀ + C μ(u) in monomials μ (a change of
/// basis of the Lagrange form, equal to rounding), and a polytope holding its Bézier control
/// points, hence the facet (the convex-hull property), to prune closest-point searches.
class PolynomialFacet {
 public:
  /// The facet of `basis` (its type and order) with nodes X (d × n, the basis's ordering).
  /// rim_edge[k] (3D): its reference edge from corner k to k + 1 has no neighbour in S;
  /// rim_corner[k]: corner k lies on such an edge (2D: has no neighbour).
  PolynomialFacet(const LagrangeBasis& basis, const Eigen::MatrixXd& X, const std::array<bool, 4>& rim_edge,
                  const std::array<bool, 4>& rim_corner);

  ElementType type() const;
  /// φ at the Newton start samples (2p + 1 per direction of the reference facet), d × s.
  const Eigen::MatrixXd& samples() const { return samples_; }
  FacetPoint evaluate(const FacetParam& u) const;
  FacetVec position(const FacetParam& u) const;
  /// The box of the control points (z = 0 in 2D), padded by 1e-9 of its diagonal for rounding.
  const Eigen::Vector3d& lo() const { return lo_; }
  const Eigen::Vector3d& hi() const { return hi_; }
  /// A lower bound of the squared distance from x (z = 0 in 2D) to the facet: to its box and
  /// to each plane bounding its control points (the two parallel to the mid-facet tangent
  /// plane, and one through each corner edge (3D) or corner (2D), normal to that plane).
  double lower_bound2(const Eigen::Vector3d& x) const;
  /// The closest point of the facet to x: Newton on ½|φ(u) − x|² from the nearest sample,
  /// then along each reference edge when it ends on the facet's boundary. `rim` from
  /// the constructor's flags.
  FacetHit closest(const Eigen::VectorXd& x) const;

 private:
  FacetPoint closest_on_segment(const Eigen::VectorXd& x, const FacetParam& a, const FacetParam& b) const;
  int corner_at(const FacetParam& u) const;

  const FacetShape* shape_;
  std::array<bool, 4> rim_edge_, rim_corner_;
  FacetVec origin_;         // x₀: the first node, so that C carries no offset's rounding
  FacetCoeffs C_;           // monomial coefficients of φ − x₀
  Eigen::MatrixXd samples_; // d × s: φ at the shape's sample parameters
  Eigen::Vector3d lo_, hi_;
  std::array<Eigen::Vector3d, 4> edge_lo_, edge_hi_;  // 3D: the box of each edge's control points
  int n_planes_ = 0;
  std::array<Eigen::Vector3d, 6> normals_;  // unit, outward
  std::array<double, 6> offsets_{};         // normal · y ≤ offset on the control points
};

/// −T G⁻¹ B (G − σB)⁻¹ Tᵀ, symmetrized (G = TᵀT, B = n·S): the derivative of the unit normal
/// n of the foot point q at a point σ from it along n.
Eigen::MatrixXd shape_hessian(const FacetPoint& q, const Eigen::VectorXd& n, double sigma);

/// |projection of −g onto T·K|, K the reference directions du that stay in the facet from
/// q.u (ε-active within 1e-8): the steepest first-order descent into the facet from q.
double cone_descent(const FacetPoint& q, const Eigen::VectorXd& g);

}  // namespace meshmorph::detail
