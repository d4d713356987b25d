// SPDX-License-Identifier: MIT
#pragma once
#include <memory>
#include <string>

#include "meshmorph/solve/linear_solver.h"

namespace meshmorph::detail {

/// Conjugate gradients in PETSc's KSP with an algebraic multigrid preconditioner:
/// aggregation (PCGAMG, "petsc-gamg") with the rigid-body modes of the options'
/// coordinates as near-null space (the block_size constant vectors without them), or hypre's
/// BoomerAMG with nodal coarsening of the block_size unknowns of a node ("petsc-hypre").
/// The matrix is copied into PETSc (A need not outlive factorize()); its copy is rebuilt only
/// when the pattern changes and otherwise refilled in place. Like CgAmgSolver, GAMG keeps its
/// prolongators across factorize() calls of one pattern (only the coarse operators are
/// recomputed) until CG needs twice the iterations per digit it needed after the last full
/// set-up. PETSc is initialized on the first construction (solve/petsc_runtime.h). PETSc is not
/// thread-safe: a process's PETSc solvers are made and used by one thread at a time.
class PetscSolver final : public LinearSolver {
 public:
  /// options.kind must be PetscGamg or PetscHypre.
  explicit PetscSolver(const LinearSolverOptions& options);
  ~PetscSolver() override;
  PetscSolver(const PetscSolver&) = delete;
  PetscSolver& operator=(const PetscSolver&) = delete;

  /// False when the preconditioner's set-up fails (e.g. on a matrix that is not positive
  /// definite); the object stays usable.
  bool factorize(const Eigen::SparseMatrix<double>& A) override;
  /// Stops when ‖b − Ax‖ ≤ rtol·‖b‖ on the true residual (CG restarts from it when the
  /// recurrence's has drifted), on negative curvature (indefinite) or after max_iterations.
  LinearSolveStats solve(const Eigen::VectorXd& b, Eigen::VectorXd& x, double rtol = 0.0,
                         double decrease = 0.0) override;
  /// CG on A with the preconditioner of the last factorize() (same pattern required).
  LinearSolveStats solve_previous(const Eigen::SparseMatrix<double>& A, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                                  double rtol = 0.0, double decrease = 0.0) override;
  std::string name() const override;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace meshmorph::detail
