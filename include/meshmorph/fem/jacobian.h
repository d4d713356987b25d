// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>

#include <Eigen/Core>

#include "meshmorph/fem/shape_table.h"
#include "meshmorph/mesh/mesh.h"

namespace meshmorph {

/// Coordinates of the nodes of one cell: dim × n_nodes_per_cell (column a = node a).
Eigen::MatrixXd cell_coordinates(const Mesh& mesh, const CellBlock& block, std::size_t cell);

/// Element Jacobian A = ∂x/∂ξ = X · ∇N at point q of a table (dim × dim); X is the
/// dim × n nodal matrix of the element. Coefficient-wise products: Eigen's GEMM would pack
/// its operands for each of these d × d results.
template <int d>
Eigen::Matrix<double, d, d> jacobian(const Eigen::Matrix<double, d, Eigen::Dynamic>& X,
                                     const ShapeTable& table, int q) {
  return X.lazyProduct(table.grad(q));
}

inline Eigen::MatrixXd jacobian(const Eigen::MatrixXd& X, const ShapeTable& table, int q) {
  return X.lazyProduct(table.grad(q));
}

}  // namespace meshmorph
