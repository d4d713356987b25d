// SPDX-License-Identifier: MIT
#pragma once
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace meshmorph {

/// Which backend solves the SPD systems of Newton steps and baselines.
enum class LinearSolverKind {
  Auto,       ///< Cholesky below a size threshold (and in 2D), Iterative above it in 3D
  Cholesky,   ///< CHOLMOD supernodal LLᵀ; symbolic analysis reused while the pattern is unchanged
  Iterative,  ///< conjugate gradients preconditioned by smoothed-aggregation algebraic multigrid
  /// MINRES preconditioned by the diagonal (paper 003's solver): a baseline to compare
  /// against, never chosen by Auto
  MinresJacobi,
  /// PETSc: conjugate gradients preconditioned by aggregation multigrid (GAMG), with the rigid
  /// body modes of the options' coordinates as near-null space; never chosen by Auto
  PetscGamg,
  /// PETSc: conjugate gradients preconditioned by hypre's BoomerAMG with nodal coarsening of
  /// each node's block_size unknowns; never chosen by Auto. PETSc is not thread-safe: the
  /// PETSc solvers of a process are made and used by one thread at a time.
  PetscHypre,
};

struct LinearSolverOptions {
  LinearSolverKind kind = LinearSolverKind::Auto;
  /// Unknowns per node (the d of d×d node blocks); the iterative backend aggregates whole
  /// nodes and uses the d constant vectors per component as near-null space.
  int block_size = 1;
  /// Spatial dimension of the problem (Auto's choice depends on it).
  int dim = 2;
  /// The most nodes of a cell of the mesh (max_cell_nodes()): how dense the Hessian's rows
  /// are, which Auto's choice depends on too. 0: unknown (taken as linear cells).
  int cell_nodes = 0;
  /// Default relative residual tolerance ‖b − Ax‖ ≤ rtol·‖b‖ of the iterative backend.
  double rtol = 1e-9;
  int max_iterations = 2000;
  int threads = 0;  ///< OpenMP threads; 0 = the OpenMP default
  /// Where the unknowns' nodes are: block_size coordinates per block of block_size unknowns
  /// (n values in all), for PetscGamg's rigid-body near-null space. Empty, or of another
  /// size: the block_size constant vectors instead. The other backends ignore it.
  std::vector<double> coordinates;
};

/// What one solve did.
struct LinearSolveStats {
  bool ok = false;           ///< false: not positive definite, or no convergence
  int iterations = 0;        ///< CG iterations (0 for a direct solve)
  double relative_residual = 0.0;
  bool indefinite = false;   ///< stopped on negative curvature: A is not positive definite
  std::string message;       ///< why it failed, empty when ok
};

/// Solves A x = b for sparse symmetric positive definite A stored with both triangles
/// (column-major, the pattern of EnergyAssembler). One object is kept across the Newton steps
/// of a run: the symbolic work (ordering, analysis, aggregation hierarchy's structure where
/// possible) is redone only when the pattern changes (other size or nnz or index arrays).
/// The iterative backend reads A again in solve(): A must stay alive and unchanged between
/// factorize() and the solves with it. The direct backend reports relative_residual = 0
/// (not computed). With block_size > 1 the unknowns are taken as consecutive blocks of
/// block_size per node (n must be a multiple of it, else the nodes are single unknowns).
class LinearSolver {
 public:
  virtual ~LinearSolver() = default;
  /// Numeric set-up for the values of `A`. Returns false when A is found not to be positive
  /// definite (a Cholesky pivot ≤ 0); the object then stays usable for another factorize().
  virtual bool factorize(const Eigen::SparseMatrix<double>& A) = 0;
  /// Solves with the last factorized matrix; `x` is the initial guess for the iterative
  /// backend (resized and zeroed when its size is wrong) and the solution on return.
  /// `rtol` ≤ 0 means the options' rtol. Iterative: stops with ok = false when it meets
  /// negative curvature (A not SPD) or reaches max_iterations. `decrease` > 0: an iterative
  /// solve also stops, ok, after one iteration at least, once ½ rᵀM⁻¹r ≤ decrease for its
  /// residual r and preconditioner M (M⁻¹ standing in for A⁻¹): for a Newton system, the model
  /// decrease that the residual leaves undone is below it (docs/morph.md, "Stopping a Newton
  /// solve"). The direct solve and the PETSc backends ignore it.
  virtual LinearSolveStats solve(const Eigen::VectorXd& b, Eigen::VectorXd& x, double rtol = 0.0,
                                 double decrease = 0.0) = 0;
  /// Solves A x = b with the set-up of the last successful factorize(), made for an earlier
  /// matrix of A's pattern, as the preconditioner of conjugate gradients on A (the iterative
  /// backend keeps A as the matrix of later solves). Between Newton steps this replaces a new
  /// factorization while the old one still preconditions well. `x` is the initial guess as
  /// in solve(), and so are `rtol` and `decrease`. ok = false when there is no
  /// such set-up (the default for backends that do not offer it), when A shows negative
  /// curvature, or when the tolerance is not reached within the backend's budget.
  virtual LinearSolveStats solve_previous(const Eigen::SparseMatrix<double>& A, const Eigen::VectorXd& b,
                                          Eigen::VectorXd& x, double rtol = 0.0, double decrease = 0.0);
  /// The iterative backend's first coarse level: P (unknowns × coarse unknowns, columns in
  /// whole blocks of block_size per coarse node), in place of the first aggregation. For
  /// high-order meshes the vertex hats (energy/coarse_space.h), which keep the set-up's
  /// products as sparse as on the linear mesh. Takes effect at the next factorize(); the
  /// other backends ignore it.
  virtual void set_coarse_space(const Eigen::SparseMatrix<double>& /*P*/) {}
  /// Whether solve_previous() costs little next to factorize() (a few preconditioned
  /// iterations with a direct factor, not a multigrid-preconditioned Krylov solve).
  virtual bool cheap_previous() const { return false; }
  /// "cholmod", "cg-amg", "minres-jacobi", "petsc-gamg" or "petsc-hypre".
  virtual std::string name() const = 0;
};

/// The backend for a system of `n` unknowns (Auto resolved here).
std::unique_ptr<LinearSolver> make_linear_solver(const LinearSolverOptions& options, std::size_t n);

/// Auto's choice for n unknowns in `dim` dimensions, on a mesh whose cells have at most
/// `cell_nodes` nodes: Cholesky in 2D, up to 30k unknowns in 3D, and up to 300k for cells of
/// 20 nodes or more (P3 tetrahedra, P2 and P3 hexahedra); CG-AMG beyond.
LinearSolverKind resolve_linear_solver(LinearSolverKind kind, int dim, std::size_t n, int cell_nodes = 0);

}  // namespace meshmorph
