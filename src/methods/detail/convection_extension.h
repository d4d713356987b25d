// SPDX-License-Identifier: MIT
#pragma once
#include <Eigen/SparseCore>

#include "methods/detail/scalar_fe.h"

namespace meshmorph::detail {

/// The SUPG-stabilized matrix of −div(k ∇v) + div(v b) = 0 (paper 004, eq. 3.8) with
/// k = α (diffusion_distance)² and b = β ∇(wind_potential), both interpolated with the cell's
/// basis: row a, column b = ∫ k ∇N_b·∇N_a − N_b (b·∇N_a) + τ (b·∇N_a)(b·∇N_b). The
/// convective term is integrated by parts (exact for P1, whose ∇ε is discontinuous across
/// cells), and the SUPG residual keeps its convective part b·∇v only: exact for P1, where
/// Δv and div b vanish in every cell, and an O(h^p) inconsistency for order p ≥ 2.
/// `conservative` = false replaces div(v b) by b·∇v (Galerkin N_a (b·∇N_b)): the
/// displacement is carried unchanged along the rays instead of thinning out with their spread.
Eigen::SparseMatrix<double> convection_diffusion_matrix(const ScalarAssembler& assembler, const Eigen::VectorXd& diffusion_distance,
                                                        const Eigen::VectorXd& wind_potential, double alpha, double beta,
                                                        bool conservative);

}  // namespace meshmorph::detail
