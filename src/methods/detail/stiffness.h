// SPDX-License-Identifier: MIT
#pragma once
#include <string_view>

#include <Eigen/SparseCore>

#include "meshmorph/methods/baselines.h"

namespace meshmorph::detail {

/// Which bilinear form assemble_stiffness integrates.
enum class StiffnessKind { Laplace, Elastic };

struct StiffnessParams {
  StiffnessKind kind = StiffnessKind::Laplace;
  double lambda = 0.0;  ///< Lamé λ (Elastic)
  double mu = 0.0;      ///< Lamé μ (Elastic)
  double chi = 0.0;     ///< stiffening exponent (Elastic): weight (J₀/J)^χ per quadrature point
  int threads = 0;
};

/// The stiffness matrix of every cell block of the input mesh over all dim·n_nodes DOFs
/// (interleaved, dof = dim·node + k): full symmetric CSC with d×d node blocks on the pattern
/// of Topology::node_nodes, exactly symmetric. Laplace puts the scalar matrix ∫∇N_a·∇N_b on
/// every component. Parallel over a cell colouring, bit-identical for any thread count.
/// Throws InputError (naming `method`) if det A ≤ 0 at a quadrature point of an input cell.
Eigen::SparseMatrix<double> assemble_stiffness(const Mesh& mesh, const Topology& topology,
                                               const StiffnessParams& params, std::string_view method);

/// Solves K u = 0 under the conditions of `bc` (see laplace_morph) with one linear solve and
/// returns x_input + u. The kernel of K is the translations, plus the infinitesimal rotations
/// when `rotations_in_kernel` (elasticity); throws InputError (naming `method`) when the
/// constraints leave a kernel mode free or the factorization fails (a singular system).
BaselineResult solve_constrained(const Mesh& mesh, const BoundaryTargets& bc, const Eigen::SparseMatrix<double>& K,
                                 bool rotations_in_kernel, const BaselineOptions& options, std::string_view method);

}  // namespace meshmorph::detail
