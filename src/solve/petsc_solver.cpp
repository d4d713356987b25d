// SPDX-License-Identifier: MIT
#include "solve/detail/petsc_solver.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include <petscksp.h>

#include "meshmorph/error.h"
#include "meshmorph/solve/petsc_runtime.h"
#include "meshmorph/threads.h"
#include "meshmorph/timings.h"

namespace meshmorph::detail {
namespace {

static_assert(sizeof(PetscInt) == sizeof(int) && sizeof(PetscScalar) == sizeof(double),
              "PETSc must be built with 32-bit indices and real double scalars (Eigen's int and double)");

// This library's entries in PETSc's (process-wide) options database: each preconditioner
// reads its own prefix, where the defaults below go unless PETSC_OPTIONS has set them.
constexpr const char* k_gamg_prefix = "meshmorph_gamg_";
constexpr const char* k_hypre_prefix = "meshmorph_hypre_";

// GAMG: aggregation on the squared graph at the first level (aggressive coarsening) with
// the prolongator left unsmoothed. On the 13.5k-node shell (35k unknowns, 2 threads, loaded
// machine) GAMG's defaults kept 11k unknowns at level 1 (operator complexity 4.4) and set up
// in 13 s; squared, smoothed: 2.5–4.3 s, 10 CG iterations to 1e-6; squared, unsmoothed:
// 0.6–0.7 s, 13 iterations, which costs less in all.
constexpr const char* k_gamg_options[][2] = {
    {"pc_gamg_type", "agg"},
    {"pc_gamg_aggressive_coarsening", "1"},
    {"pc_gamg_agg_nsmooths", "0"},
};

// BoomerAMG for systems: nodal coarsening (strength between nodes by the Frobenius norm of
// their d×d blocks), HMIS coarsening with extended+i interpolation (hypre's 3D choices in
// place of PETSc's Falgout/classical defaults), strong threshold 0.5 as hypre's manual advises
// for 3D, aggressive coarsening on the first level (on the 13.5k shell: set-up 1.8 s → 0.7 s,
// 6 → 9 CG iterations), and l1-scaled symmetric Gauss–Seidel, which keeps the V-cycle
// symmetric for CG.
constexpr const char* k_hypre_options[][2] = {
    {"pc_hypre_type", "boomeramg"},
    {"pc_hypre_boomeramg_nodal_coarsen", "1"},
    {"pc_hypre_boomeramg_coarsen_type", "HMIS"},
    {"pc_hypre_boomeramg_interp_type", "ext+i"},
    {"pc_hypre_boomeramg_strong_threshold", "0.5"},
    {"pc_hypre_boomeramg_P_max", "4"},
    {"pc_hypre_boomeramg_agg_nl", "1"},
    {"pc_hypre_boomeramg_relax_type_all", "l1scaled-SOR/Jacobi"},
};

template <std::size_t n>
void set_defaults(const char* prefix, const char* const (&options)[n][2]) {
  for (const auto& [key, value] : options) {
    const std::string name = std::string("-") + prefix + key;
    PetscBool set = PETSC_FALSE;
    PetscOptionsHasName(nullptr, nullptr, name.c_str(), &set);
    if (!set) PetscOptionsSetValue(nullptr, name.c_str(), value);
  }
}

struct Check {
  const char* what;
  void operator()(PetscErrorCode e) const {
    if (e != 0) throw std::runtime_error(std::string("meshmorph: PETSc ") + what + " failed (error " + std::to_string(static_cast<int>(e)) + ")");
  }
};

// Gives a vector its own (empty) array back when a solve ends, thrown out of or not.
struct Placed {
  Vec v;
  ~Placed() { VecResetArray(v); }
};

}  // namespace

}  // namespace meshmorph::detail

namespace meshmorph {

const char* gamg_options_prefix() {
  ensure_petsc();
  detail::set_defaults(detail::k_gamg_prefix, detail::k_gamg_options);
  return detail::k_gamg_prefix;
}

}  // namespace meshmorph

namespace meshmorph::detail {

struct PetscSolver::Impl {
  LinearSolverOptions options;
  KSP ksp = nullptr;
  Mat A = nullptr;
  Vec b = nullptr, x = nullptr, r = nullptr;  // b and x wrap the caller's arrays during a solve
  std::vector<int> outer, inner;              // A's pattern
  bool sorted_rows = true;  // PETSc keeps each row's columns sorted: values then copy as they are
  bool ready = false;
  bool built = false;       // a full GAMG set-up exists for A's pattern
  bool rebuild = false;     // the next factorize() does a full set-up
  double base_cost = -1.0;  // CG iterations per digit right after the last full set-up

  bool gamg() const { return options.kind == LinearSolverKind::PetscGamg; }
  int n() const { return outer.empty() ? 0 : static_cast<int>(outer.size()) - 1; }
  bool same_pattern(const Eigen::SparseMatrix<double>& M) const {
    return A != nullptr && M.rows() == n() && M.nonZeros() == static_cast<Eigen::Index>(inner.size()) &&
           std::equal(outer.begin(), outer.end(), M.outerIndexPtr()) &&
           std::equal(inner.begin(), inner.end(), M.innerIndexPtr());
  }
  void create_ksp();
  void destroy_matrix();
  void create_matrix(const Eigen::SparseMatrix<double>& M);
  void fill(const Eigen::SparseMatrix<double>& M);
  LinearSolveStats cg(const Eigen::VectorXd& bv, Eigen::VectorXd& xv, double rtol);
  void track(const LinearSolveStats& stats);
};

void PetscSolver::Impl::destroy_matrix() {
  VecDestroy(&b), VecDestroy(&x), VecDestroy(&r);
  MatDestroy(&A);
  outer.clear(), inner.clear();
  built = false;
}

// A symmetric matrix in compressed columns is its own compressed rows: the arrays go to
// PETSc's AIJ as they are. The near-null space is set on the matrix, where GAMG finds it.
void PetscSolver::Impl::create_matrix(const Eigen::SparseMatrix<double>& M) {
  const Check check{"matrix set-up"};
  if (A != nullptr) {  // a new solver object: PCGAMG's levels keep the sizes they were made for
    KSPDestroy(&ksp);
    create_ksp();
  }
  destroy_matrix();
  const int size = static_cast<int>(M.rows());
  outer.assign(M.outerIndexPtr(), M.outerIndexPtr() + size + 1);
  inner.assign(M.innerIndexPtr(), M.innerIndexPtr() + M.nonZeros());
  sorted_rows = true;
  for (int i = 0; i < size && sorted_rows; ++i) sorted_rows = std::is_sorted(inner.begin() + outer[i], inner.begin() + outer[i + 1]);
  const int bs = options.block_size > 1 && size % options.block_size == 0 ? options.block_size : 1;
  check(MatCreate(PETSC_COMM_SELF, &A));
  check(MatSetSizes(A, size, size, size, size));
  check(MatSetType(A, MATSEQAIJ));
  check(MatSetBlockSize(A, bs));
  check(MatSeqAIJSetPreallocationCSR(A, outer.data(), inner.data(), M.valuePtr()));
  check(MatSetOption(A, MAT_SYMMETRIC, PETSC_TRUE));
  check(MatSetOption(A, MAT_SYMMETRY_ETERNAL, PETSC_TRUE));
  check(VecCreateSeqWithArray(PETSC_COMM_SELF, bs, size, nullptr, &b));
  check(VecCreateSeqWithArray(PETSC_COMM_SELF, bs, size, nullptr, &x));
  check(MatCreateVecs(A, &r, nullptr));
  if (gamg() && bs > 1 && options.coordinates.size() == static_cast<std::size_t>(size)) {
    Vec coordinates = nullptr;
    check(VecCreateSeqWithArray(PETSC_COMM_SELF, bs, size, options.coordinates.data(), &coordinates));
    MatNullSpace rigid = nullptr;
    const PetscErrorCode e = MatNullSpaceCreateRigidBody(coordinates, &rigid);
    VecDestroy(&coordinates);
    check(e);
    check(MatSetNearNullSpace(A, rigid));
    MatNullSpaceDestroy(&rigid);
  }
}

void PetscSolver::Impl::fill(const Eigen::SparseMatrix<double>& M) {
  const Check check{"matrix update"};
  if (sorted_rows) {
    PetscScalar* values = nullptr;
    check(MatSeqAIJGetArray(A, &values));
    std::memcpy(values, M.valuePtr(), sizeof(double) * inner.size());
    check(MatSeqAIJRestoreArray(A, &values));
    return;
  }
  for (int i = 0; i < n(); ++i)
    check(MatSetValues(A, 1, &i, outer[i + 1] - outer[i], inner.data() + outer[i], M.valuePtr() + outer[i], INSERT_VALUES));
  check(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
  check(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
}

void PetscSolver::Impl::create_ksp() {
  const Check check{"solver set-up"};
  check(KSPCreate(PETSC_COMM_SELF, &ksp));
  check(KSPSetType(ksp, KSPCG));
  // ‖b − Ax‖, the residual of the interface's tolerance, not the preconditioned one.
  check(KSPSetNormType(ksp, KSP_NORM_UNPRECONDITIONED));
  check(KSPSetInitialGuessNonzero(ksp, PETSC_TRUE));
  PC pc = nullptr;
  check(KSPGetPC(ksp, &pc));
  if (gamg()) {
    check(PCSetType(pc, PCGAMG));
    check(PCSetOptionsPrefix(pc, gamg_options_prefix()));
  } else {
    check(PCSetType(pc, PCHYPRE));
    set_defaults(k_hypre_prefix, k_hypre_options);
    check(PCSetOptionsPrefix(pc, k_hypre_prefix));
  }
  check(PCSetFromOptions(pc));
}

PetscSolver::PetscSolver(const LinearSolverOptions& options) : impl_(std::make_unique<Impl>()) {
  MESHMORPH_CHECK(options.kind == LinearSolverKind::PetscGamg || options.kind == LinearSolverKind::PetscHypre,
                  "PetscSolver: the kind must be PetscGamg or PetscHypre");
  ensure_petsc();
  impl_->options = options;
  impl_->create_ksp();
}

PetscSolver::~PetscSolver() {
  PetscBool finalized = PETSC_TRUE;
  if (PetscFinalized(&finalized) != 0 || finalized) return;  // at exit, PETSc may be gone first
  impl_->destroy_matrix();
  KSPDestroy(&impl_->ksp);
}

std::string PetscSolver::name() const { return impl_->gamg() ? "petsc-gamg" : "petsc-hypre"; }

bool PetscSolver::factorize(const Eigen::SparseMatrix<double>& A) {
  const PhaseTimer timer(Phase::SolverSetup);
  MESHMORPH_CHECK(A.rows() == A.cols() && A.isCompressed(), "petsc: the matrix must be square and compressed");
  Impl& s = *impl_;
  s.ready = false;
  const ScopedThreads threads(s.options.threads);
  const bool same = s.same_pattern(A);
  if (same)
    s.fill(A);
  else
    s.create_matrix(A);
  if (A.rows() == 0) return s.ready = true;
  // The prolongators of the last full set-up serve later matrices of the pattern, with their
  // coarse operators recomputed, until CG's cost per digit doubles (as in CgAmgSolver).
  const bool reuse = s.gamg() && same && s.built && !s.rebuild;
  PC pc = nullptr;
  const Check check{"preconditioner set-up"};
  check(KSPGetPC(s.ksp, &pc));
  if (s.gamg()) check(PCGAMGSetReuseInterpolation(pc, reuse ? PETSC_TRUE : PETSC_FALSE));
  check(KSPSetReusePreconditioner(s.ksp, PETSC_FALSE));
  check(KSPSetOperators(s.ksp, s.A, s.A));
  if (KSPSetUp(s.ksp) != 0) {
    s.rebuild = true;
    return false;
  }
  if (!reuse) {
    s.built = true;
    s.rebuild = false;
    s.base_cost = -1.0;
  }
  return s.ready = true;
}

LinearSolveStats PetscSolver::solve_previous(const Eigen::SparseMatrix<double>& A, const Eigen::VectorXd& b,
                                             Eigen::VectorXd& x, double rtol, double /*decrease*/) {
  const PhaseTimer timer(Phase::Solve);
  Impl& s = *impl_;
  if (!s.ready || !s.same_pattern(A)) {
    LinearSolveStats stats;
    stats.message = "no preconditioner of this pattern to reuse";
    return stats;
  }
  {
    const ScopedThreads threads(s.options.threads);
    s.fill(A);
    const Check check{"operator update"};
    check(KSPSetReusePreconditioner(s.ksp, PETSC_TRUE));
    check(KSPSetOperators(s.ksp, s.A, s.A));
  }
  return solve(b, x, rtol);
}

LinearSolveStats PetscSolver::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x, double rtol, double /*decrease*/) {
  const PhaseTimer timer(Phase::Solve);
  Impl& s = *impl_;
  const ScopedThreads threads(s.options.threads);
  const LinearSolveStats stats = s.cg(b, x, rtol);
  s.track(stats);
  return stats;
}

void PetscSolver::Impl::track(const LinearSolveStats& stats) {
  if (!stats.ok) {
    rebuild = rebuild || !stats.indefinite;
    return;
  }
  if (stats.iterations < 3 || !(stats.relative_residual > 0.0)) return;
  const double cost = stats.iterations / std::max(1.0, -std::log10(stats.relative_residual));
  if (base_cost < 0.0)
    base_cost = cost;
  else if (cost > 2.0 * base_cost + 1.0)
    rebuild = true;
}

LinearSolveStats PetscSolver::Impl::cg(const Eigen::VectorXd& bv, Eigen::VectorXd& xv, double rtol) {
  LinearSolveStats stats;
  if (!ready) {
    stats.message = "no preconditioner set up";
    return stats;
  }
  const int size = n();
  MESHMORPH_CHECK(bv.size() == size, "petsc: right-hand side of the wrong size");
  if (rtol <= 0.0) rtol = options.rtol;
  if (xv.size() != size) xv = Eigen::VectorXd::Zero(size);
  const double b_norm = bv.norm();
  if (b_norm == 0.0) {
    xv.setZero();
    stats.ok = true;
    return stats;
  }
  const Check check{"solve"};
  check(VecPlaceArray(b, bv.data()));  // read only: KSPSolve does not write its right-hand side
  const Placed placed_b{b};
  check(VecPlaceArray(x, xv.data()));
  const Placed placed_x{x};
  // The test is absolute, rtol·‖b‖ on CG's recurrence residual (PETSc's relative test would
  // measure against the initial residual); the true residual decides, and CG restarts from
  // it when rounding has let the two drift apart.
  KSPConvergedReason reason = KSP_CONVERGED_ITERATING;
  double r_norm = 0.0;
  while (true) {
    check(KSPSetTolerances(ksp, 0.0, rtol * b_norm, 1e300, std::max(1, options.max_iterations - stats.iterations)));
    const PetscErrorCode e = KSPSolve(ksp, b, x);
    PetscInt its = 0;
    KSPGetIterationNumber(ksp, &its);
    stats.iterations += static_cast<int>(its);
    KSPGetConvergedReason(ksp, &reason);
    check(MatMult(A, x, r));
    check(VecAYPX(r, -1.0, b));
    check(VecNorm(r, NORM_2, &r_norm));
    if (e != 0 || reason <= 0 || r_norm <= rtol * b_norm || its == 0 || stats.iterations >= options.max_iterations) break;
  }
  stats.relative_residual = r_norm / b_norm;
  stats.ok = reason > 0 && r_norm <= rtol * b_norm;
  if (stats.ok) return stats;
  if (reason == KSP_DIVERGED_INDEFINITE_MAT) {
    stats.indefinite = true;
    stats.message = "matrix not positive definite";
  } else if (reason == KSP_DIVERGED_INDEFINITE_PC) {
    stats.message = "preconditioner not positive definite";
  } else if (reason == KSP_DIVERGED_ITS || reason > 0) {
    stats.message = std::string(gamg() ? "petsc-gamg" : "petsc-hypre") + ": no convergence in " + std::to_string(stats.iterations) + " iterations";
  } else {
    stats.message = std::string("petsc: CG stopped (") + KSPConvergedReasons[reason] + ")";
  }
  return stats;
}

}  // namespace meshmorph::detail
