// SPDX-License-Identifier: MIT
#pragma once
#include <Eigen/SparseCore>

#include "methods/detail/scalar_fe.h"

namespace meshmorph::detail {

/// Residual R_a = ∫ h ∇ε·∇N_a + (|∇ε|² − 1) N_a of the stabilized Eikonal equation at the
/// nodal values `eps` (all nodes), and its Jacobian J_ab = ∂R_a/∂ε_b =
/// ∫ h ∇N_b·∇N_a + 2 (∇ε·∇N_b) N_a (row a, column b).
void eikonal_residual(const ScalarAssembler& assembler, const Eigen::VectorXd& eps, double h, Eigen::VectorXd& R,
                      Eigen::SparseMatrix<double>& J);

}  // namespace meshmorph::detail
