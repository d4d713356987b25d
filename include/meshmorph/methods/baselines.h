// SPDX-License-Identifier: MIT
#pragma once
#include <Eigen/Core>

#include "meshmorph/methods/boundary_targets.h"
#include "meshmorph/mesh/topology.h"
#include "meshmorph/solve/linear_solver.h"

namespace meshmorph {

/// Parameters of the two baseline methods (`"options": {"method": "laplace" | "elastic"}`).
struct BaselineOptions {
  LinearSolverKind solver = LinearSolverKind::Auto;  ///< backend of the one linear solve
  /// Jacobian-based stiffening exponent χ of `elastic` (Tezduyar et al.): the stiffness at a
  /// quadrature point is scaled by (J₀/J)^χ, so small elements are stiffer. 0 = none.
  double stiffening = 1.0;
  double poisson_ratio = 0.3;  ///< ν of `elastic` (Young's modulus E = 1; it cancels out)
  int threads = 0;             ///< OpenMP threads for assembly and solve; 0 = the OpenMP default
};

/// What a baseline produced.
struct BaselineResult {
  Eigen::MatrixXd x;       ///< dim × n_nodes: the morphed node positions
  /// The one linear solve (ok = true and no solve when nothing is free). ok = false: the
  /// iterative backend stopped short of its tolerance, and x holds its last iterate.
  LinearSolveStats linear;
  int linear_solves = 1;   ///< 1, or 0 when every node is constrained
};

/// Component-wise Laplacian mesh motion: the displacement u = x − x_input solves
/// ∫ ∇u_k·∇v = 0 (k = 1..d) on the *input* mesh, with the Lagrange basis of each cell block's
/// own type and order, for all v vanishing on the constrained nodes.
///
/// Boundary conditions per node (BoundaryTargets): Prescribed: u = target − x_input, and the
/// node ends exactly on `target`; Fixed: u = 0; Slide: n·u = 0 with the tangential components
/// free (eliminated exactly by a local basis {t₁, …, t_{d−1}} of the slide plane, which couples
/// the components at those nodes); Free: unknown (natural, zero-traction condition on free
/// boundary nodes). Nodes in no cell stay where they are. Reproduces any affine boundary motion
/// exactly on any mesh. One assembly and one linear solve (block size d without Slide nodes).
///
/// Throws InputError when no node is Fixed or Prescribed (the system is singular), when the
/// matrix is found not to be positive definite, when a Slide normal is zero, or when the input
/// mesh has an element with det J ≤ 0 at a quadrature point.
BaselineResult laplace_morph(const Mesh& mesh, const Topology& topology, const BoundaryTargets& bc,
                             const BaselineOptions& options = {});

/// Linear-elastic mesh motion with Jacobian-based stiffening: u solves
/// ∫ (J₀/J)^χ (λ div u div v + 2μ ε(u):ε(v)) = 0 on the *input* mesh, E = 1, ν =
/// `poisson_ratio` (plane strain in 2D), λ = Eν/((1+ν)(1−2ν)), μ = E/(2(1+ν)).
///
/// J is the element volume measure at the quadrature point, det A · |reference cell| (so
/// simplices and tensor cells of one size get the same J in a mixed mesh); J₀ is its mean
/// over all quadrature points of the mesh. A constant J₀ scales the whole matrix and does
/// not change u; it only keeps the entries of order one. χ = 0 gives plain linear elasticity,
/// which reproduces every affine boundary motion exactly; with χ > 0 that holds only when J
/// is constant (uniform meshes) or the motion is a translation (zero strain).
///
/// Boundary conditions, exceptions and cost as laplace_morph. The constrained nodes must
/// remove the rigid motions (e.g. not a single Fixed node in 2D); a system found not positive
/// definite throws InputError. Also throws InputError for χ < 0 or ν outside (−1, 0.5).
BaselineResult elastic_morph(const Mesh& mesh, const Topology& topology, const BoundaryTargets& bc,
                             const BaselineOptions& options = {});

}  // namespace meshmorph
