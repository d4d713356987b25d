// SPDX-License-Identifier: MIT
#pragma once
#include <array>

#include <Eigen/Core>

#include "meshmorph/fem/tensor_basis.h"
#include "meshmorph/mesh/element_type.h"

namespace meshmorph::detail {

/// n choose k, in double.
double binomial(int n, int k);

/// The Bernstein polynomials of degree q on [0, 1] at the points i/q: M(i, k) = B_k(i/q).
Eigen::MatrixXd segment_bernstein(int q);

/// The regular lattice of order m on the unit simplex, the unit box [0, 1]^d or the unit
/// triangle × [0, 1] (prisms) (dim × N, x fastest); on pyramids, the lattice of the collapsed
/// box (u, v, ζ) ∈ [−1, 1]² × [0, 1] below the apex, as points (u(1 − ζ), v(1 − ζ), ζ): the validity samples' order-2p lattice, and the points whose values give the
/// Bernstein coefficients of det A.
Eigen::MatrixXd unit_lattice(ElementType type, int m);

/// det A at the points of a tensor grid (X: dim × n nodes), NaN as −∞, by sum factorization.
template <int d>
void dets_on_grid(const TensorGrid& g, const Eigen::MatrixXd& X, Eigen::VectorXd& v);

/// Whether det A of a simplex or tensor cell of (type, order) can dip below its sampled values
/// and is bounded by the expansion below: it is constant on linear simplices and bilinear on
/// linear quadrilaterals (extreme at the corners, which are samples); elsewhere it is a
/// polynomial that sampling alone cannot bound. False on prisms and pyramids, which have
/// their own bounds (prism_min_det, pyramid_min_det).
bool det_needs_bounds(ElementType type, int order);

/// The Bernstein coefficients of det A of one cell (X: dim × n nodes) of a type and order that
/// det_needs_bounds, in the order of unit_lattice(type, degree of det A).
Eigen::VectorXd det_bernstein_coefficients(ElementType type, int order, const Eigen::MatrixXd& X);

/// The lowest det A of one cell (X: dim × n nodes) that its Bernstein (Bézier) expansion
/// finds, for a cell whose samples are all positive (Johnen, Remacle & Geuzaine, "Geometrical
/// validity of curvilinear finite elements", J. Comput. Phys. 233, 2013): det A is a
/// polynomial, of total degree d(p − 1) on a simplex of order p and of degree dp − 1 in each
/// variable on a tensor cell, and it lies between the least and the largest of its Bernstein
/// coefficients, which its values at the lattice of that degree give exactly. All
/// coefficients positive: valid, and `sampled` is returned. A value ≤ 0 at a lattice point:
/// that value is returned (the cell is invalid). Otherwise the cell is bisected (longest edge
/// in reference coordinates; the halves' coefficients by de Casteljau's algorithm) and its
/// halves examined alike: a corner coefficient ≤ 0, or det A ≤ 0 where the least coefficient
/// lies, is returned; down to 2^−(6d) of its size, cells still undecided there are taken as
/// valid (what sampling alone said).
/// Prisms go to prism_min_det; linear pyramids return `sampled` (pyramid_min_det), others go
/// to pyramid_bounds_min_det.
double bezier_min_det(ElementType type, int order, const Eigen::MatrixXd& X, double sampled);

/// The degrees of det A on a prism of order p: 3p − 2 (total) in (ξ, η), 3p − 1 in ζ.
std::array<int, 2> prism_det_degrees(int order);

/// The Bernstein coefficients of det A of one prism (X: 3 × n nodes) on the product of the
/// triangle's Bernstein polynomials of degree 3p − 2 and the segment's of degree 3p − 1, in
/// the order of unit_lattice(Prism, ·) restricted to that product (triangle index fastest,
/// then ζ).
Eigen::VectorXd prism_det_coefficients(int order, const Eigen::MatrixXd& X);

/// The lowest det A of one prism whose samples are all positive, as bezier_min_det does on
/// other cells: det A is a polynomial, of total degree 3p − 2 in (ξ, η) and of degree 3p − 1
/// in ζ (the prism is the triangle × the segment), between the least and the largest of its
/// coefficients on the product Bernstein basis. All positive: `sampled`; a lattice value ≤ 0:
/// that value; else the prism is bisected (the longer of its triangle's longest edge and half
/// its ζ-extent), each half's coefficients from det A at its own lattice, to 2^−18 of its size
/// and 512 pieces, undecided pieces then taken as valid (what sampling said).
double prism_min_det(int order, const Eigen::MatrixXd& X, double sampled);

/// The linear pyramid needs no expansion. Its map is x = Σ x_a N_a with the rational basis of
/// lagrange_basis.h; with u = ξ/(1 − ζ), v = η/(1 − ζ) ∈ [−1, 1], the columns of A are
/// a_ξ + c v, a_η + c u and a_ζ + c u v (c = (x₀ − x₁ + x₂ − x₃)/4), so, c appearing in two
/// columns at most once, det A = det(a_ξ, a_η, a_ζ) + v det(c, a_η, a_ζ) + u det(a_ξ, c, a_ζ)
/// + u v det(a_ξ, a_η, c): bilinear in (u, v) and independent of ζ. Its least value over the
/// pyramid is at (u, v) = (±1, ±1), the four base corners, which are validity samples: the
/// sampled minimum is exact (a certificate). This returns that minimum, det A at the corners.
double pyramid_min_det(const Eigen::MatrixXd& X);

/// The lowest det A of one pyramid of order p ≥ 2 whose samples are all positive. With
/// u = ξ/(1 − ζ), v = η/(1 − ζ), det A = det(X G(u, v, ζ)) (pyramid_collapsed_gradients) is a
/// polynomial on the box [−1, 1]² × [0, 1], of degree 3p − 1 in u and v and 3(p − 1) in ζ,
/// bounded by its tensor Bernstein coefficients: all positive: `sampled`; a lattice value ≤ 0 (the lattice holds
/// the apex): that value; else the box is halved as prism_min_det halves prisms.
double pyramid_bounds_min_det(int order, const Eigen::MatrixXd& X, double sampled);

}  // namespace meshmorph::detail
