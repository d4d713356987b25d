// SPDX-License-Identifier: MIT
#include "solve/detail/cg_amg_solver.h"

#include <algorithm>
#include <cmath>

#include "meshmorph/error.h"
#include "meshmorph/threads.h"
#include "meshmorph/timings.h"

namespace meshmorph::detail {
namespace {

// y += a·x
void axpy(double a, const Eigen::VectorXd& x, Eigen::VectorXd& y, int threads) {
  const int n = static_cast<int>(x.size());
#pragma omp parallel for num_threads(threads) schedule(static)
  for (int i = 0; i < n; ++i) y[i] += a * x[i];
}

}  // namespace

AmgOptions amg_options(const LinearSolverOptions& options) {
  AmgOptions amg;
  amg.block_size = std::max(1, options.block_size);
  amg.threads = resolve_threads(options.threads);
  return amg;
}

CgAmgSolver::CgAmgSolver(const LinearSolverOptions& options, const AmgOptions& amg)
    : options_(options), amg_(amg) {}
CgAmgSolver::CgAmgSolver(const LinearSolverOptions& options) : CgAmgSolver(options, amg_options(options)) {}

bool CgAmgSolver::factorize(const Eigen::SparseMatrix<double>& A) {
  const PhaseTimer timer(Phase::SolverSetup);
  ready_ = false;
  const bool same_pattern = built_ && A.rows() == A_.n && A.nonZeros() == nnz_;
  A_ = view_of(A);
  nnz_ = A_.nnz();
  if (A_.n == 0) return ready_ = true;
  // The prolongators of the last full set-up serve matrices of the same pattern, with their
  // coarse operators recomputed (refresh), until CG needs twice the iterations per digit that
  // it needed right after that set-up (Newton steps change the Hessian little; a jump of the
  // penalty or a failure triggers a rebuild).
  if (same_pattern && !rebuild_ && amg_.refresh(A_)) return ready_ = true;
  built_ = ready_ = amg_.setup(A_);
  rebuild_ = false;
  base_cost_ = -1.0;
  return ready_;
}

void CgAmgSolver::track(const LinearSolveStats& stats) {
  if (!stats.ok) {
    rebuild_ = rebuild_ || !stats.indefinite;  // an indefinite matrix is no fault of the preconditioner
    return;
  }
  if (stats.iterations < 3 || !(stats.relative_residual > 0.0)) return;
  const double cost = stats.iterations / std::max(1.0, -std::log10(stats.relative_residual));  // iterations per digit
  if (base_cost_ < 0.0)
    base_cost_ = cost;
  else if (cost > 2.0 * base_cost_ + 1.0)
    rebuild_ = true;
}

void CgAmgSolver::set_coarse_space(const Eigen::SparseMatrix<double>& P) {
  const Eigen::SparseMatrix<double, Eigen::RowMajor> rows = P;  // sorted column indices per row
  Csr first;
  first.rows = static_cast<int>(rows.rows());
  first.cols = static_cast<int>(rows.cols());
  first.ptr.assign(rows.outerIndexPtr(), rows.outerIndexPtr() + rows.rows() + 1);
  first.idx.assign(rows.innerIndexPtr(), rows.innerIndexPtr() + rows.nonZeros());
  first.val.assign(rows.valuePtr(), rows.valuePtr() + rows.nonZeros());
  amg_.set_first_prolongator(std::move(first));
  built_ = ready_ = false;
}

LinearSolveStats CgAmgSolver::solve_previous(const Eigen::SparseMatrix<double>& A, const Eigen::VectorXd& b,
                                             Eigen::VectorXd& x, double rtol, double decrease) {
  const PhaseTimer timer(Phase::Solve);
  if (!ready_ || A.rows() != A_.n || A.nonZeros() != nnz_) {
    LinearSolveStats stats;
    stats.message = "no preconditioner of this pattern to reuse";
    return stats;
  }
  A_ = view_of(A);
  if (A_.n > 0 && !amg_.rebind(A_)) {
    ready_ = false;
    LinearSolveStats stats;
    stats.message = "the new matrix does not fit the old preconditioner";
    return stats;
  }
  return solve(b, x, rtol, decrease);
}

LinearSolveStats CgAmgSolver::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x, double rtol, double decrease) {
  const PhaseTimer timer(Phase::Solve);
  const LinearSolveStats stats = cg(b, x, rtol, decrease);
  track(stats);
  return stats;
}

LinearSolveStats CgAmgSolver::cg(const Eigen::VectorXd& b, Eigen::VectorXd& x, double rtol, double decrease) {
  LinearSolveStats stats;
  if (!ready_) {
    stats.message = "matrix not positive definite";
    return stats;
  }
  const int n = A_.n;
  MESHMORPH_CHECK(b.size() == n, "cg-amg: right-hand side of the wrong size");
  const int threads = resolve_threads(options_.threads);
  if (rtol <= 0.0) rtol = options_.rtol;
  if (x.size() != n) x = Eigen::VectorXd::Zero(n);
  r_.resize(n), z_.resize(n), p_.resize(n), q_.resize(n);
  const double b_norm = std::sqrt(dot(b.data(), b.data(), n, threads));
  if (b_norm == 0.0) {
    x.setZero();
    stats.ok = true;
    return stats;
  }
  residual(A_, b.data(), x.data(), r_.data(), threads);
  double r_norm = std::sqrt(dot(r_.data(), r_.data(), n, threads));
  // CG on the recurrence residual; at its convergence the true residual is checked and CG
  // restarts from it if rounding has let the two drift apart. Where the decrease left is
  // below `decrease`, the recurrence's is trusted: its drift is far below the residual there.
  bool small_decrease = false;
  while (r_norm > rtol * b_norm && !small_decrease && stats.iterations < options_.max_iterations) {
    amg_.apply(r_.data(), z_.data());
    double rz = dot(r_.data(), z_.data(), n, threads);
    p_ = z_;
    while (stats.iterations < options_.max_iterations) {
      if (!(rz > 0.0)) {
        stats.message = "preconditioner not positive definite";
        stats.relative_residual = r_norm / b_norm;
        return stats;
      }
      amg_.apply_operator(p_.data(), q_.data());
      const double pq = dot(p_.data(), q_.data(), n, threads);
      ++stats.iterations;
      if (!(pq > 0.0)) {
        stats.indefinite = true;
        stats.message = "matrix not positive definite";
        stats.relative_residual = r_norm / b_norm;
        return stats;
      }
      const double alpha = rz / pq;
      axpy(alpha, p_, x, threads);
      axpy(-alpha, q_, r_, threads);
      r_norm = std::sqrt(dot(r_.data(), r_.data(), n, threads));
      if (r_norm <= rtol * b_norm) break;
      amg_.apply(r_.data(), z_.data());
      const double rz_new = dot(r_.data(), z_.data(), n, threads);
      small_decrease = 0.5 * rz_new <= decrease;
      if (small_decrease) break;
      const double beta = rz_new / rz;
      rz = rz_new;
#pragma omp parallel for num_threads(threads) schedule(static)
      for (int i = 0; i < n; ++i) p_[i] = z_[i] + beta * p_[i];
    }
    if (small_decrease) break;
    residual(A_, b.data(), x.data(), r_.data(), threads);
    r_norm = std::sqrt(dot(r_.data(), r_.data(), n, threads));
  }
  stats.relative_residual = r_norm / b_norm;
  stats.ok = r_norm <= rtol * b_norm || small_decrease;
  if (!stats.ok) stats.message = "cg-amg: no convergence in " + std::to_string(stats.iterations) + " iterations";
  return stats;
}

}  // namespace meshmorph::detail
