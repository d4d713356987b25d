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

}  // namespace meshmorph
