// SPDX-License-Identifier: MIT
#pragma once
#include <string>

#include "solve/detail/amg.h"

namespace meshmorph::detail {

/// Conjugate gradients preconditioned by one smoothed-aggregation V-cycle ("cg-amg").
/// factorize() rebuilds the hierarchy for the new values and keeps a view of A: A must stay
/// alive and unchanged until the solves with it are done.
class CgAmgSolver final : public LinearSolver {
 public:
  CgAmgSolver(const LinearSolverOptions& options, const AmgOptions& amg);
  explicit CgAmgSolver(const LinearSolverOptions& options);

  bool factorize(const Eigen::SparseMatrix<double>& A) override;
  LinearSolveStats solve(const Eigen::VectorXd& b, Eigen::VectorXd& x, double rtol = 0.0,
                         double decrease = 0.0) override;
  LinearSolveStats solve_previous(const Eigen::SparseMatrix<double>& A, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                                  double rtol = 0.0, double decrease = 0.0) override;
  void set_coarse_space(const Eigen::SparseMatrix<double>& P) override;
  std::string name() const override { return "cg-amg"; }

  const AmgHierarchy& hierarchy() const { return amg_; }

 private:
  LinearSolveStats cg(const Eigen::VectorXd& b, Eigen::VectorXd& x, double rtol, double decrease);
  void track(const LinearSolveStats& stats);  // decides when the hierarchy is rebuilt
  LinearSolverOptions options_;
  AmgHierarchy amg_;
  SparseView A_{};  // the matrix of the solves: it must outlive them (see LinearSolver)
  std::int64_t nnz_ = 0;  // A_'s at factorize(), read without touching A_ (which may be gone)
  bool ready_ = false;
  bool built_ = false;     // a full set-up exists (for A_'s pattern)
  bool rebuild_ = false;   // the next factorize() does a full set-up
  double base_cost_ = -1;  // CG iterations per digit right after the last full set-up
  Eigen::VectorXd r_, z_, p_, q_;
};

/// The hierarchy's parameters for a solver's options (block size, threads).
AmgOptions amg_options(const LinearSolverOptions& options);

}  // namespace meshmorph::detail
