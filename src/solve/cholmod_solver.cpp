// SPDX-License-Identifier: MIT
#include "solve/detail/cholmod_solver.h"

#include <algorithm>
#include <cstring>
#include <utility>
#include <vector>

#include <cholmod.h>
#include <dlfcn.h>
#include <omp.h>

#include "meshmorph/error.h"
#include "meshmorph/timings.h"
#include "solve/detail/cholmod_header.h"
#include "solve/detail/float_factor.h"

namespace meshmorph::detail {

SparseView view_of(const Eigen::SparseMatrix<double>& A) {
  MESHMORPH_CHECK(A.rows() == A.cols(), "linear solver: the matrix is not square");
  MESHMORPH_CHECK(A.isCompressed(), "linear solver: the matrix is not compressed");
  return SparseView{static_cast<int>(A.rows()), A.outerIndexPtr(), A.innerIndexPtr(), A.valuePtr()};
}

// OpenBLAS (when it is the system BLAS) starts its own thread pool, which fights the OpenMP
// threads of the element loops for the same cores and makes small factorizations several
// times slower (measured: 10 s instead of 1.6 s on a 2D case). One BLAS thread per call,
// except in the factorizations of systems of k_threaded_blas_min unknowns and more.
void set_blas_threads(int n) {
  using SetThreads = void (*)(int);
  static const auto set = reinterpret_cast<SetThreads>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"));
  if (set) set(n);
}
constexpr int k_threaded_blas_min = 50000;

void single_threaded_blas() {
  static const bool done = [] {
    set_blas_threads(1);
    return true;
  }();
  (void)done;
}

// CHOLMOD's supernodal factorization opens an OpenMP region for each update of a supernode
// by a descendant, about 0.45 µs each with libgomp even when one thread runs it, and makes
// its BLAS calls per supernode. On 2D Hessians the supernodes of its default amalgamation are
// narrow (9–12 columns on average; 17–19 on 3D ones) and those fixed costs take a third of a
// factorization (2.5M regions in 495 factorizations of a 7k-unknown rotor Hessian). Where the
// mean width is below k_narrow_supernodes, the pattern is analysed again with the same
// ordering and looser amalgamation: supernodes of up to 8 columns merge whatever their
// zeros, up to 32 with 80% of zeros or fewer, up to 64 with 20%, larger ones with 10%
// (CHOLMOD's nrelax and zrelax; the defaults are 4, 16, 48 and 80%, 10%, 5%). On the 2D
// benchmarks a factorization then takes 13–27% less time although L holds 28–47% more
// entries; on 3D Hessians it took up to 21% longer, so they keep the defaults.
namespace {

constexpr double k_narrow_supernodes = 15.0;

cholmod_factor* analyze(cholmod_sparse* A, cholmod_common* c) {
  cholmod_factor* L = cholmod_analyze(A, c);
  if (!L || c->status < CHOLMOD_OK || !L->is_super ||
      static_cast<double>(L->n) >= k_narrow_supernodes * static_cast<double>(L->nsuper))
    return L;
  const int* perm = static_cast<const int*>(L->Perm);
  std::vector<int> given(perm, perm + L->n);
  // The looser settings go in for this one analysis and the common's own come back after.
  std::size_t nrelax[3] = {8, 32, 64};
  double zrelax[3] = {0.8, 0.2, 0.1};
  int nmethods = 1;
  auto method = c->method[0];
  method.ordering = CHOLMOD_GIVEN;
  const auto swap_settings = [&] {
    std::swap(c->nrelax, nrelax);
    std::swap(c->zrelax, zrelax);
    std::swap(c->nmethods, nmethods);
    std::swap(c->method[0], method);
  };
  swap_settings();
  cholmod_factor* relaxed = cholmod_analyze_p(A, given.data(), nullptr, 0, c);
  const int status = c->status;
  swap_settings();
  if (!relaxed || status < CHOLMOD_OK) {  // keep the first analysis
    if (relaxed) cholmod_free_factor(&relaxed, c);
    c->status = CHOLMOD_OK;
    return L;
  }
  cholmod_free_factor(&L, c);
  return relaxed;
}

}  // namespace

struct CholmodSolver::Impl {
  cholmod_common common{};
  cholmod_factor* factor = nullptr;
  FloatFactor single;  // solve_previous's preconditioner, copied from `factor` when first needed

  Impl() {
    single_threaded_blas();
    cholmod_start(&common);
    // The library never prints: CHOLMOD reports through `common.status` only.
    common.print = 0;
    common.error_handler = nullptr;
    common.supernodal = CHOLMOD_SUPERNODAL;
    common.quick_return_if_not_posdef = 1;
  }
  ~Impl() {
    if (factor) cholmod_free_factor(&factor, &common);
    cholmod_finish(&common);
  }
};

CholmodSolver::CholmodSolver() : impl_(std::make_unique<Impl>()) {}
CholmodSolver::~CholmodSolver() = default;

int CholmodSolver::n_supernodes() const {
  return impl_->factor && impl_->factor->is_super ? static_cast<int>(impl_->factor->nsuper) : 0;
}

bool CholmodSolver::factorize(const Eigen::SparseMatrix<double>& A) { return factorize(view_of(A)); }

bool CholmodSolver::factorize(const SparseView& A) {
  const PhaseTimer timer(Phase::SolverSetup);
  factorized_ = false;
  impl_->single.clear();
  const std::size_t nnz = static_cast<std::size_t>(A.nnz());
  const bool same_pattern = impl_->factor != nullptr && outer_.size() == static_cast<std::size_t>(A.n) + 1 &&
                            inner_.size() == nnz && std::equal(outer_.begin(), outer_.end(), A.outer) &&
                            std::equal(inner_.begin(), inner_.end(), A.inner);
  cholmod_sparse S = cholmod_header(A);
  cholmod_common* c = &impl_->common;
  if (!same_pattern) {
    if (impl_->factor) cholmod_free_factor(&impl_->factor, c);
    outer_.assign(A.outer, A.outer + A.n + 1);
    inner_.assign(A.inner, A.inner + nnz);
    impl_->factor = analyze(&S, c);
    ++n_analyses_;
    if (!impl_->factor || c->status < CHOLMOD_OK) {
      outer_.clear();
      inner_.clear();
      if (c->status == CHOLMOD_OUT_OF_MEMORY) throw std::bad_alloc();
      throw std::runtime_error("cholmod: symbolic analysis failed (status " + std::to_string(c->status) + ")");
    }
  }
  int ok = 0;
  // CHOLMOD's supernodal factorization opens OpenMP regions of four threads for its copies
  // into each large supernode; those short regions cost more in thread wake-ups than they
  // save (measured: 0.09 s → 0.06 s per factorization at 10k unknowns with one thread, 0.2 s
  // and more when two threads are allowed). A host teams region caps them at one thread; the
  // dense work goes to BLAS.
  // Large factorizations are BLAS-bound and nothing else runs meanwhile: BLAS gets the OpenMP
  // threads for them (optimize on 95k–108k-unknown P2 Hessians, 2 threads: 12–19% less time
  // for the whole run), and one thread again after.
  const int blas_threads = A.n >= k_threaded_blas_min ? omp_get_max_threads() : 1;
  if (blas_threads > 1) set_blas_threads(blas_threads);
#pragma omp teams num_teams(1) thread_limit(1)
  ok = cholmod_factorize(&S, impl_->factor, c);
  if (blas_threads > 1) set_blas_threads(1);
  if (c->status == CHOLMOD_OUT_OF_MEMORY) throw std::bad_alloc();
  if (!ok || c->status == CHOLMOD_NOT_POSDEF || impl_->factor->minor < impl_->factor->n) return false;
  // A failed numeric factorization may leave the factor simplicial/symbolic; the next call
  // refactorizes into it, which CHOLMOD supports without a new analysis.
  factorized_ = true;
  return true;
}

void CholmodSolver::solve(const double* b, double* x) {
  MESHMORPH_CHECK(factorized_, "cholmod: solve() without a successful factorize()");
  cholmod_factor* L = impl_->factor;
  cholmod_dense B{};
  B.nrow = L->n;
  B.ncol = 1;
  B.nzmax = L->n;
  B.d = L->n;
  B.x = const_cast<double*>(b);
  B.xtype = CHOLMOD_REAL;
  B.dtype = CHOLMOD_DOUBLE;
  cholmod_dense* X = cholmod_solve(CHOLMOD_A, L, &B, &impl_->common);
  if (!X) throw std::bad_alloc();
  std::memcpy(x, X->x, L->n * sizeof(double));
  cholmod_free_dense(&X, &impl_->common);
}

LinearSolveStats CholmodSolver::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x, double /*rtol*/,
                                      double /*decrease*/) {
  const PhaseTimer timer(Phase::Solve);
  LinearSolveStats stats;
  if (!factorized_) {
    stats.message = "matrix not positive definite";
    return stats;
  }
  MESHMORPH_CHECK(static_cast<std::size_t>(b.size()) == impl_->factor->n, "cholmod: right-hand side of the wrong size");
  x.resize(b.size());
  solve(b.data(), x.data());
  stats.ok = x.allFinite();
  if (!stats.ok) stats.message = "cholmod: solution not finite";
  return stats;
}

LinearSolveStats CholmodSolver::solve_previous(const Eigen::SparseMatrix<double>& A, const Eigen::VectorXd& b,
                                               Eigen::VectorXd& x, double rtol, double decrease) {
  const PhaseTimer timer(Phase::Solve);
  LinearSolveStats stats;
  if (!(factorized_ && A.rows() + 1 == static_cast<Eigen::Index>(outer_.size()) &&
        A.nonZeros() == static_cast<Eigen::Index>(inner_.size()))) {
    stats.message = "no factorization of this pattern to reuse";
    return stats;
  }
  // Conjugate gradients on A preconditioned by the old factor, read in single precision
  // (FloatFactor). A pair of triangular solves costs a few hundredths of a factorization in
  // 3D, so a handful of iterations is the budget; beyond it a new factorization is cheaper.
  constexpr int k_max_iterations = 12;
  const double b_norm = b.norm();
  const double tol = (rtol > 0.0 ? rtol : 1e-9) * b_norm;
  if (x.size() != b.size()) x.setZero(b.size());
  FloatFactor& M = impl_->single;
  if (M.empty()) {
    const cholmod_factor* L = impl_->factor;
    MESHMORPH_CHECK(L->is_super && L->itype == CHOLMOD_INT && L->Perm, "cholmod: the factor is not supernodal (with its permutation)");
    M.assign(static_cast<int>(L->n), static_cast<int>(L->nsuper), static_cast<const int*>(L->super),
             static_cast<const int*>(L->pi), static_cast<const int*>(L->px), static_cast<const int*>(L->s),
             static_cast<const double*>(L->x), static_cast<const int*>(L->Perm));
  }
  Eigen::VectorXd r = b - A * x, z(b.size()), p(b.size()), q(b.size());
  M.solve(r.data(), z.data());
  p = z;
  double rz = r.dot(z);
  double r_norm = r.norm();
  bool small_decrease = false;
  while (r_norm > tol && stats.iterations < k_max_iterations) {
    q.noalias() = A * p;
    const double pq = p.dot(q);
    if (!(pq > 0.0)) {
      stats.indefinite = true;
      stats.message = "negative curvature: the matrix is not positive definite";
      return stats;
    }
    const double alpha = rz / pq;
    x += alpha * p;
    r -= alpha * q;
    ++stats.iterations;
    r_norm = r.norm();
    if (r_norm <= tol) break;
    M.solve(r.data(), z.data());
    const double rz_new = r.dot(z);
    if (0.5 * rz_new <= decrease) {
      small_decrease = true;
      break;
    }
    p = z + (rz_new / rz) * p;
    rz = rz_new;
  }
  stats.relative_residual = b_norm > 0.0 ? r_norm / b_norm : 0.0;
  stats.ok = (r_norm <= tol || small_decrease) && x.allFinite();
  if (!stats.ok && stats.message.empty())
    stats.message = "the previous factorization no longer preconditions well enough";
  return stats;
}

}  // namespace meshmorph::detail
