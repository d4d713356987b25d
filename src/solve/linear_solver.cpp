// SPDX-License-Identifier: MIT
#include "meshmorph/solve/linear_solver.h"

#include "solve/detail/cg_amg_solver.h"
#include "solve/detail/cholmod_solver.h"
#include "solve/detail/minres_jacobi_solver.h"
#include "solve/detail/petsc_solver.h"

namespace meshmorph {

LinearSolveStats LinearSolver::solve_previous(const Eigen::SparseMatrix<double>& /*A*/, const Eigen::VectorXd& /*b*/,
                                              Eigen::VectorXd& /*x*/, double /*rtol*/, double /*decrease*/) {
  LinearSolveStats stats;
  stats.message = "no earlier set-up to reuse";
  return stats;
}

LinearSolverKind resolve_linear_solver(LinearSolverKind kind, int dim, std::size_t n, int cell_nodes) {
  if (kind != LinearSolverKind::Auto) return kind;
  // Measured on projected 3D P1 tetrahedral Hessians (bench/linear_solver_bench.cpp, two
  // threads, CHOLMOD on OpenBLAS): factorize + solve takes 0.14 s at 10k unknowns, 0.54 s at
  // 24k and 2.3 s at 53k, against 0.08, 0.20 and 0.44 s for CG-AMG to 1e-6. Cholesky is kept
  // up to ~30k unknowns, where it costs under a second and does not depend on conditioning
  // (the penalty of an augmented Lagrangian reaches 1e9 times the mesh stiffness).
  constexpr std::size_t k_cholesky_max_3d = 30000;
  // High-order cells couple a node with hundreds of unknowns. CG-AMG with the vertex hats as
  // its first coarse level (the methods' set_coarse_space) still takes more CG iterations
  // than a factorization costs up to a few hundred thousand unknowns. Measured (2 threads):
  // morph bl_sphere_p3 (115k P3-tet unknowns) 205 s and 0.4 GB with it, 44–50 s and 1.6 GB
  // with CHOLMOD (aggregating the P3 Hessian itself: 353 s); fit of the 64³ CSG mesh (250k
  // P2-hex unknowns) 8 s a step and 2.6 GB with CHOLMOD.
  constexpr int k_dense_cell_nodes = 20;
  constexpr std::size_t k_cholesky_max_dense_3d = 300000;
  if (dim <= 2 || n <= k_cholesky_max_3d) return LinearSolverKind::Cholesky;
  if (cell_nodes >= k_dense_cell_nodes && n <= k_cholesky_max_dense_3d) return LinearSolverKind::Cholesky;
  return LinearSolverKind::Iterative;
}

std::unique_ptr<LinearSolver> make_linear_solver(const LinearSolverOptions& options, std::size_t n) {
  switch (resolve_linear_solver(options.kind, options.dim, n, options.cell_nodes)) {
    case LinearSolverKind::Iterative: return std::make_unique<detail::CgAmgSolver>(options);
    case LinearSolverKind::MinresJacobi: return std::make_unique<detail::MinresJacobiSolver>(options);
    case LinearSolverKind::PetscGamg:
    case LinearSolverKind::PetscHypre: return std::make_unique<detail::PetscSolver>(options);
    default: return std::make_unique<detail::CholmodSolver>();
  }
}

}  // namespace meshmorph
