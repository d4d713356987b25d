// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "meshmorph/mesh/element_type.h"

namespace meshmorph {

/// The Lagrange basis of a quadrilateral or hexahedron as a tensor product of a 1D basis,
/// for sum factorization: N_a(ξ) = Π_k l_{i_k}(ξ_k) where local node a sits at lattice index
/// i_0 + P(i_1 + P i_2) of the 1D nodes.
struct TensorBasis {
  /// 1D nodes; 0 where (type, order) is not a tensor product of them (simplices).
  int P = 0;
  std::vector<double> nodes;         ///< the 1D nodes, ascending
  std::vector<std::int32_t> node;    ///< local node at lattice index i_0 + P(i_1 + P i_2)

  /// B(q, i) = l_i(x_q) and D(q, i) = l_i'(x_q) at the 1D points x (size m × P).
  void tabulate(const std::vector<double>& x, Eigen::MatrixXd& B, Eigen::MatrixXd& D) const;
};

/// The shared tensor basis of (type, order) (P = 0 outside quadrilaterals and hexahedra).
const TensorBasis& tensor_basis(ElementType type, int order);

/// A tensor basis at the m^dim points of a tensor grid of 1D points x (x fastest: point
/// q_0 + m(q_1 + m q_2)), for sum factorization.
struct TensorGrid {
  const TensorBasis* basis = nullptr;
  int dim = 0, m = 0;
  Eigen::MatrixXd B, D;  ///< m × P: TensorBasis::tabulate at x
};

/// The grid of (type, order)'s tensor basis at x; basis null where it has none.
TensorGrid tensor_grid(ElementType type, int order, const std::vector<double>& x);

/// G(k, dim·q + j) = Σ_a X(k, a) ∂N_a/∂ξ_j at grid point q (column-major, c × dim·m^dim),
/// for X with c rows, one column per local node: three (two) 1D passes,
/// O(m P^dim + m² P^(dim−1) + ...) instead of the O(m^dim P^dim) of X ∇N.
void grid_gradients(const TensorGrid& g, const double* X, int c, double* G);
/// The transpose: Y(k, a) = Σ_q Σ_j R(k, dim·q + j) ∂N_a/∂ξ_j at point q (R as G, Y as X).
void grid_gradients_transpose(const TensorGrid& g, const double* R, int c, double* Y);

}  // namespace meshmorph
