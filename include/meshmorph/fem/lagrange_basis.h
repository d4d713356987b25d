// SPDX-License-Identifier: MIT
#pragma once
#include <array>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "meshmorph/fem/reference_element.h"

namespace meshmorph {

/// The nodal Lagrange basis of a reference element: N_a(ξ_b) = δ_ab at its nodes. Complete
/// polynomials of degree p on simplices and tensor-product degree p on quads and hexes, built
/// by inverting the Vandermonde matrix of a monomial basis at the nodes; on prisms the
/// products L_i(ξ, η) ℓ_k(ζ) of the triangle's and the segment's nodal bases (every prism
/// node is a triangle node at a segment node). The pyramid's space
/// is not polynomial: the pyramidal space of Bergot, Cohen and Duruflé ("Higher-order finite
/// elements for hybrid meshes using new nodal pyramidal elements", J. Sci. Comput. 42, 2010),
/// which is Gmsh's, spanned by u^i v^j (1 − ζ)^max(i,j) ζ^k (u = ξ/(1 − ζ), v = η/(1 − ζ),
/// i, j ≤ p, k ≤ p − max(i, j)); order 1: span{1, ξ, η, ζ, ξη/(1 − ζ)}, whose nodal functions
/// are (1 − ζ)(1 ± u)(1 ± v)/4 and ζ. Gradients are bounded but have no limit at the apex,
/// where they are not evaluated (quadrature and validity samples avoid it).
class LagrangeBasis {
 public:
  LagrangeBasis(ElementType type, int order);

  ElementType type() const { return ref_->type; }
  int order() const { return ref_->order; }
  int dim() const { return ref_->dim; }
  int n() const { return ref_->n_nodes(); }
  const ReferenceElement& reference() const { return *ref_; }

  /// N(a) = N_a(ξ); ξ has dim() entries.
  Eigen::VectorXd values(const Eigen::VectorXd& xi) const;
  /// G(a, k) = ∂N_a/∂ξ_k, an n × dim matrix.
  Eigen::MatrixXd gradients(const Eigen::VectorXd& xi) const;
  /// H(a, k·dim + l) = ∂²N_a/∂ξ_k∂ξ_l, an n × dim² matrix (symmetric in k, l).
  Eigen::MatrixXd hessians(const Eigen::VectorXd& xi) const;

 private:
  const ReferenceElement* ref_;
  Eigen::MatrixXi exponents_;  // dim × n monomial exponents (empty on prisms and pyramids)
  Eigen::MatrixXd coeffs_;     // n × n: N_a = Σ_m coeffs_(m, a) · monomial_m (pyramids: pyramidal function m)
  std::vector<std::array<int, 2>> factors_;  // prisms: node a = (triangle node, segment node)
  std::shared_ptr<const LagrangeBasis> triangle_, segment_;  // prisms: the factors' bases
};

/// The shared basis of (type, order).
const LagrangeBasis& lagrange_basis(ElementType type, int order);

}  // namespace meshmorph
