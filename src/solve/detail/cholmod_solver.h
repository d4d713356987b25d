// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "meshmorph/solve/linear_solver.h"

namespace meshmorph::detail {

/// A square sparse matrix in compressed columns (or rows: the matrices here are symmetric
/// and stored with both triangles, so one is the other), 0-based int indices, sorted.
struct SparseView {
  int n = 0;
  const int* outer = nullptr;   ///< n + 1 offsets
  const int* inner = nullptr;   ///< outer[n] indices
  const double* values = nullptr;
  std::int64_t nnz() const { return n > 0 ? outer[n] : 0; }
};

/// The view of a compressed Eigen matrix (no copy); throws when `A` is not square or not
/// compressed.
SparseView view_of(const Eigen::SparseMatrix<double>& A);

/// CHOLMOD supernodal LLᵀ of a symmetric positive definite matrix (the upper triangle of the
/// full storage is read, stype = 1). The symbolic analysis (fill-reducing ordering, supernodes)
/// is kept and reused while the pattern (n, nnz, index arrays) stays the same.
class CholmodSolver final : public LinearSolver {
 public:
  CholmodSolver();
  ~CholmodSolver() override;
  CholmodSolver(const CholmodSolver&) = delete;
  CholmodSolver& operator=(const CholmodSolver&) = delete;

  bool factorize(const Eigen::SparseMatrix<double>& A) override;
  LinearSolveStats solve(const Eigen::VectorXd& b, Eigen::VectorXd& x, double rtol = 0.0,
                         double decrease = 0.0) override;
  LinearSolveStats solve_previous(const Eigen::SparseMatrix<double>& A, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                                  double rtol = 0.0, double decrease = 0.0) override;
  bool cheap_previous() const override { return true; }
  std::string name() const override { return "cholmod"; }

  /// The same on a raw view (the coarse level of the multigrid hierarchy).
  bool factorize(const SparseView& A);
  /// x = A⁻¹ b for the last successful factorize(); b and x may alias.
  void solve(const double* b, double* x);
  /// Number of symbolic analyses done so far (one per distinct pattern).
  int n_analyses() const { return n_analyses_; }
  /// Supernodes of the current analysis (0 before the first). Where CHOLMOD's default
  /// amalgamation leaves them narrow (2D Hessians), the analysis merges more of them.
  int n_supernodes() const;
  /// True when the last factorize() succeeded.
  bool is_factorized() const { return factorized_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::vector<int> outer_, inner_;  // the analysed pattern
  int n_analyses_ = 0;
  bool factorized_ = false;
};

}  // namespace meshmorph::detail
