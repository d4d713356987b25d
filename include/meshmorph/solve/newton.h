// SPDX-License-Identifier: MIT
#pragma once
#include <functional>
#include <string>

#include <Eigen/Core>

#include "meshmorph/energy/assembler.h"
#include "meshmorph/solve/linear_solver.h"

namespace meshmorph {

/// An objective minimised by newton(): it owns the current iterate x (the free DOFs of a
/// DofMap) and evaluates the energy there and at trial points x + α p.
class NewtonProblem {
 public:
  virtual ~NewtonProblem() = default;
  /// Value, gradient and Hessian (in `mode`) at the current iterate.
  virtual void evaluate(HessianMode mode, Assembly& out) = 0;
  /// Value and gradient alone at the current iterate (`out.hessian` untouched), where the
  /// problem can give them for less than evaluate(); false where it cannot.
  virtual bool evaluate_gradient(Assembly& /*out*/) { return false; }
  /// Energy at x + α p; +∞ where it is not defined (an inverted element).
  virtual double trial_value(const Eigen::VectorXd& p, double alpha) = 0;
  /// Whether x + α p may be accepted: a check beyond the energy's own barrier (e.g. the
  /// dense validity test of curved elements), run only for steps that pass Armijo.
  virtual bool admissible(const Eigen::VectorXd& /*p*/, double /*alpha*/) { return true; }
  /// Moves the iterate to x + α p.
  virtual void accept(const Eigen::VectorXd& p, double alpha) = 0;
  /// Called after each line search: the problem may change its energy in the light of the
  /// trials that admissible() rejected (morph guards the cells that blocked them,
  /// energy/validity_guard.h). True when it did; a search that found no step is then tried
  /// again on the new energy.
  virtual bool refine() { return false; }
};

/// Diagonal blocks of a Hessian over the free DOFs: block b covers the consecutive DOFs
/// first[b] .. first[b + 1] − 1 (at most `size`: a node's) and holds their entries
/// column-major at values[b·size²], leading dimension `size`.
struct HessianBlocks {
  int size = 1;
  std::vector<std::int32_t> first;
  std::vector<double> values;
};

/// The coarse level of newton_matrix_free's two-level preconditioner: R, a coarse basis at
/// the free DOFs (n_free × n_coarse), and A = Rᵀ H R.
struct CoarseHessian {
  const Eigen::SparseMatrix<double>* R = nullptr;
  Eigen::SparseMatrix<double> A;
};

/// A NewtonProblem whose Hessian is available as an operator (for newton_matrix_free()).
class MatrixFreeNewtonProblem : public NewtonProblem {
 public:
  /// Value and gradient at the current iterate (`out.hessian` untouched) and the set-up of
  /// the Hessian's action in `mode`, for apply_hessian() and hessian_blocks().
  virtual void evaluate_action(HessianMode mode, Assembly& out) = 0;
  /// y = H v with the Hessian of the last evaluate_action().
  virtual void apply_hessian(const Eigen::VectorXd& v, Eigen::VectorXd& y) = 0;
  /// The node blocks of that Hessian (the preconditioner's).
  virtual HessianBlocks hessian_blocks() = 0;
  /// The coarse level of that Hessian; false where the problem has none.
  virtual bool coarse_hessian(CoarseHessian& /*out*/) { return false; }
};

struct NewtonOptions {
  /// Stop when the predicted decrease ½ gᵀH⁻¹g (half the squared Newton decrement: the
  /// residual in the norm of the Newton system) is ≤ this, in the energy's units.
  double decrement_tolerance = 1e-12;
  int max_iterations = 100;
  /// Steps taken before the decrement test may end the iteration: a caller whose change of
  /// the problem is below the test (morph's multiplier update near the boundary) still gets
  /// the step that answers it.
  int min_iterations = 0;
  double armijo = 1e-4;      ///< c of the Armijo rule (paper 000: 1e-4)
  double backtrack = 0.5;    ///< step reduction per rejected trial
  double min_step = 1e-12;   ///< smallest α tried before giving up
  /// Step with the exact Hessian H, modified where it is not positive definite to
  /// H + τ|diag H| with the first τ of a short increasing sequence (five factorizations at
  /// most, τ ≤ max_shift, starting near the last τ that worked; Nocedal–Wright §3.4) that
  /// makes it so: quadratic convergence near the solution, where projected-Hessian Newton
  /// converges only linearly (DESIGN §6). Otherwise the step of the SPD-projected Hessian, and
  /// the two steps after it too; always that step when false.
  bool exact_first = true;
  double max_shift = 1.0;
  /// The next step starts from a quarter of the last τ that worked while that is above
  /// min_shift, else from 0 (and from there 1e-4 if H is indefinite). morph lowers it: its
  /// weighted, penalised Hessians may need 1e-8, and full steps at 1e-4 crawled.
  double min_shift = 1e-4;
  /// Relative residual of Krylov solves (also of those with an earlier factorization).
  double linear_rtol = 1e-8;
  /// Inexact Newton where > linear_rtol: Krylov solves stop at this relative residual (the
  /// decrement test is then as loose), and a step whose line search ends below α = 0.1 is
  /// solved on to linear_rtol and searched again.
  double forcing = 0.0;
  /// Called after each accepted step with the step count and the step length α; returning
  /// false ends newton() there (NewtonStats::stopped). The caller may change the problem's
  /// parameters in it (untangle lowers δ): the next iterate is evaluated afresh.
  std::function<bool(int iteration, double alpha)> on_step;
};

struct NewtonStats {
  bool converged = false;     ///< the decrement test passed
  int iterations = 0;         ///< accepted Newton steps
  int linear_solves = 0;       ///< including the solves with an earlier factorization
  long long krylov_iterations = 0;
  double value = 0.0;         ///< energy at the final iterate
  double decrement = 0.0;     ///< ½ gᵀH⁻¹g at the last check
  bool stopped = false;       ///< NewtonOptions::on_step ended the iteration
  std::string message;        ///< why it stopped without converging
};

/// What one newton() call leaves for the next on a related problem (the same unknowns, with
/// changed parameters, e.g. the next augmented-Lagrangian subproblem).
struct NewtonMemory {
  double shift = 0.0;          ///< τ to start from
  /// Whether the solver holds a factorization of a Hessian with at most a small shift, to be
  /// tried at the next iterate before a new factorization.
  bool reusable = false;
  /// Newton matrices solved with the solver's set-up since it was made for another
  /// (solve_previous): a multigrid set-up serves at most two after its own.
  int reuses = 0;
  /// Whether the exact Hessian is worth trying (NewtonOptions::exact_first): set by a full
  /// projected step (α = 1), cleared when no small shift makes the exact Hessian positive
  /// definite. Far from a minimiser the projected Hessian's steps go much further.
  bool exact_ready = false;
  /// Whether the test after a full step is tried first from the gradient alone and the
  /// earlier factorization: cleared when that test fails, set again when the full test passes
  /// after a full step (on hard motions most steps leave the decrement above the test).
  bool test_from_gradient = true;
};

/// The inexact Newton solves of newton_matrix_free().
struct KrylovNewtonOptions {
  /// Eisenstat–Walker forcing terms (choice 2, SIAM J. Sci. Comput. 17, 1996):
  /// η_k = γ (|g_k| / |g_{k−1}|)², safeguarded by γ η_{k−1}² where that exceeds 0.1, within
  /// [min_forcing, max_forcing]; η_0 = max_forcing.
  double max_forcing = 0.1;
  /// Near a solution η_k falls fast and CG would run long for digits that the next Newton
  /// step gives anyway: on MFEM's 95k meshes 1e-3 took 20–25% less time than 1e-8, and 1e-2
  /// one more Newton step (bench/README.md).
  double min_forcing = 1e-3;
  double gamma = 0.9;
  /// CG iterations per step at most (MFEM mesh-optimizer caps MINRES at 100, `-li`); the
  /// iterate where the cap stops CG is still a descent direction.
  int max_iterations = 200;
  /// Add the problem's coarse level (MatrixFreeNewtonProblem::coarse_hessian) to block
  /// Jacobi, where it has one: M⁻¹ = B⁻¹ + R A⁻¹ Rᵀ, A factorized by CHOLMOD at every step.
  bool two_level = true;
  int threads = 0;  ///< of the coarse factorization; 0 = the OpenMP default
};

/// Inexact Newton with the Hessian as an operator (no matrix): each step solves H p = −g by
/// conjugate gradients preconditioned by H's node blocks (block Jacobi, each block's
/// eigenvalues taken in modulus, at least 1e-3 of the mean |H_ii|), plus the problem's
/// coarse level where it has one and its A factorizes (additive two-level: on MFEM's 95k
/// meshes 4–5× fewer CG iterations), from p = 0, to the relative residual η_k of
/// KrylovNewtonOptions. Every CG iterate before a direction of nonpositive curvature is a
/// descent direction (Dembo–Steihaug), and the step is the last of them. With
/// NewtonOptions::exact_first the exact Hessian is used once a projected step was taken in
/// full; nonpositive curvature in its CG solve (the step is then redone with the projected
/// Hessian), or a failed line search, return to the projected Hessian. The line search, stopping rules (decrement, taken only from a CG
/// solve that reached its tolerance) and on_step are newton()'s.
/// NewtonStats::krylov_iterations counts the CG iterations.
NewtonStats newton_matrix_free(MatrixFreeNewtonProblem& problem, const NewtonOptions& options,
                               const KrylovNewtonOptions& krylov = {});

/// Damped Newton with backtracking Armijo line search: never accepts a trial point whose
/// energy is +∞ or that is not admissible. Starts from the problem's current iterate.
///
/// Before factorizing at an iterate, Newton solves with the factorization of an earlier
/// iterate as CG preconditioner (LinearSolver::solve_previous): where that solution passes the
/// decrement test, Newton stops; otherwise it is the step, and a new factorization is due
/// only when the old one no longer preconditions well. Near a solution, and after a small
/// change of the problem's parameters, this saves most factorizations. `memory` (optional)
/// carries τ, the factorization and whether to try the exact Hessian between calls.
NewtonStats newton(NewtonProblem& problem, LinearSolver& solver, const NewtonOptions& options,
                   NewtonMemory* memory = nullptr);

}  // namespace meshmorph
