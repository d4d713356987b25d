// SPDX-License-Identifier: MIT
// Preconditioned MINRES after Elman, Silvester and Wathen (Finite Elements and Fast Iterative
// Solvers, Algorithm 2.4): a Lanczos process in the M⁻¹ inner product, M = diag(A), with the
// QR factorization of its tridiagonal matrix updated by Givens rotations. |η| is the
// M⁻¹-norm of the residual; the stopping test is on the true residual, computed whenever that
// estimate says the tolerance may have been reached.
#include "solve/detail/minres_jacobi_solver.h"

#include <algorithm>
#include <cmath>

#include "meshmorph/threads.h"
#include "meshmorph/timings.h"
#include "solve/detail/amg_csr.h"

namespace meshmorph::detail {

bool MinresJacobiSolver::factorize(const Eigen::SparseMatrix<double>& A) {
  const PhaseTimer timer(Phase::SolverSetup);
  A_ = view_of(A);
  inverse_diagonal_.setZero(A_.n);
  ready_ = false;
  for (int j = 0; j < A_.n; ++j) {
    double a = 0.0;
    for (int k = A_.outer[j]; k < A_.outer[j + 1]; ++k)
      if (A_.inner[k] == j) a = A_.values[k];
    if (!(a > 0.0)) return false;
    inverse_diagonal_[j] = 1.0 / a;
  }
  return ready_ = true;
}

LinearSolveStats MinresJacobiSolver::solve(const Eigen::VectorXd& b, Eigen::VectorXd& x, double rtol,
                                           double /*decrease*/) {
  const PhaseTimer timer(Phase::Solve);
  LinearSolveStats stats;
  if (!ready_) {
    stats.message = "no matrix factorized";
    return stats;
  }
  const int n = A_.n;
  const int threads = resolve_threads(options_.threads);
  if (rtol <= 0.0) rtol = options_.rtol;
  if (x.size() != n) x.setZero(n);
  const double b_norm = b.norm();
  if (n == 0 || b_norm == 0.0) {
    x.setZero(n);
    stats.ok = true;
    return stats;
  }
  Eigen::VectorXd v(n), v_old = Eigen::VectorXd::Zero(n), v_new(n), z(n), Az(n);
  Eigen::VectorXd w = Eigen::VectorXd::Zero(n), w_old = Eigen::VectorXd::Zero(n), w_new(n);
  residual(A_, b.data(), x.data(), v.data(), threads);
  const auto true_residual = [&] {
    residual(A_, b.data(), x.data(), v_new.data(), threads);
    return v_new.norm() / b_norm;
  };
  stats.relative_residual = v.norm() / b_norm;
  if (stats.relative_residual <= rtol) return stats.ok = true, stats;
  z = inverse_diagonal_.cwiseProduct(v);
  double gamma = std::sqrt(z.dot(v)), gamma_old = 1.0;
  double eta = gamma, c = 1.0, c_old = 1.0, s = 0.0, s_old = 0.0;
  // The M⁻¹-norm estimate that corresponds to rtol in the 2-norm, corrected from the true
  // residual whenever the two disagree.
  double target = rtol * gamma / stats.relative_residual;
  for (int it = 1; it <= options_.max_iterations; ++it) {
    z /= gamma;
    spmv(A_, z.data(), Az.data(), threads);
    const double delta = Az.dot(z);
    v_new = Az - (delta / gamma) * v - (gamma / gamma_old) * v_old;
    v_old.swap(v);
    v.swap(v_new);
    const Eigen::VectorXd z_next = inverse_diagonal_.cwiseProduct(v);
    const double gamma_new = std::sqrt(std::max(0.0, z_next.dot(v)));
    const double a0 = c * delta - c_old * s * gamma;
    const double a1 = std::hypot(a0, gamma_new);
    const double a2 = s * delta + c_old * c * gamma;
    const double a3 = s_old * gamma;
    c_old = c;
    s_old = s;
    c = a0 / a1;
    s = gamma_new / a1;
    w_new = (z - a3 * w_old - a2 * w) / a1;
    w_old.swap(w);
    w.swap(w_new);
    x += (c * eta) * w;
    eta = -s * eta;
    gamma_old = gamma;
    gamma = gamma_new;
    z = z_next;
    stats.iterations = it;
    if (std::abs(eta) <= target || gamma == 0.0) {
      stats.relative_residual = true_residual();
      if (stats.relative_residual <= rtol) return stats.ok = true, stats;
      if (gamma == 0.0) break;  // the Krylov space is exhausted
      target *= std::max(0.1, rtol / stats.relative_residual);
    }
  }
  stats.relative_residual = true_residual();
  stats.ok = stats.relative_residual <= rtol;
  if (!stats.ok) stats.message = "MINRES did not reach the tolerance within " + std::to_string(options_.max_iterations) + " iterations";
  return stats;
}

}  // namespace meshmorph::detail
