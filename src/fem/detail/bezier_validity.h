// SPDX-License-Identifier: MIT
#pragma once
#include <Eigen/Core>

#include "meshmorph/fem/tensor_basis.h"
#include "meshmorph/mesh/element_type.h"

namespace meshmorph::detail {

/// The regular lattice of order m on the unit simplex or the unit box [0, 1]^d (dim × N, x
/// fastest): the validity samples' order-2p lattice, and the points whose values give the
/// Bernstein coefficients of det A.
Eigen::MatrixXd unit_lattice(ElementType type, int m);

/// det A at the points of a tensor grid (X: dim × n nodes), NaN as −∞, by sum factorization.
template <int d>
void dets_on_grid(const TensorGrid& g, const Eigen::MatrixXd& X, Eigen::VectorXd& v);

/// Whether det A of a cell of (type, order) can dip below its sampled values: it is constant
/// on linear simplices and bilinear on linear quadrilaterals (extreme at the corners, which
/// are samples); elsewhere it is a polynomial that sampling alone cannot bound.
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
double bezier_min_det(ElementType type, int order, const Eigen::MatrixXd& X, double sampled);

}  // namespace meshmorph::detail
