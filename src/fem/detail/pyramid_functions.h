// SPDX-License-Identifier: MIT
#pragma once
#include <Eigen/Core>

namespace meshmorph::detail {

/// The pyramidal functions of order p of Bergot, Cohen and Duruflé ("Higher-order finite
/// elements for hybrid meshes using new nodal pyramidal elements", J. Sci. Comput. 42, 2010),
/// the space of Gmsh's pyramids: u^i v^j h^m ζ^k with h = 1 − ζ, u = ξ/h, v = η/h,
/// 0 ≤ i, j ≤ p, m = max(i, j), 0 ≤ k ≤ p − m ((p + 1)(p + 2)(2p + 3)/6 of them). Order 1:
/// 1, ζ, ξ, η, ξη/(1 − ζ). At the apex u = v = 0 (the values there are their limits; the
/// gradients stay finite, the Hessians do not).
///
/// `derivatives` 0: values (n × 1); 1: gradients in (ξ, η, ζ) (n × 3); 2: Hessians (n × 9,
/// column 3k + l = ∂²/∂ξ_k∂ξ_l).
Eigen::MatrixXd pyramid_functions(int order, const Eigen::Vector3d& xi, int derivatives);

/// In the collapsed coordinates (u, v, ζ) ∈ [−1, 1]² × [0, 1]: (∂f/∂u)/h, (∂f/∂v)/h and
/// ∂f/∂ζ at fixed (u, v) (n × 3), which are the columns of ∂f/∂ξ, ∂f/∂η and, less multiples
/// of the first two, ∂f/∂ζ: det A = det(X·G) with G this matrix, a polynomial in (u, v, ζ).
Eigen::MatrixXd pyramid_collapsed_gradients(int order, const Eigen::Vector3d& uvz);

}  // namespace meshmorph::detail
