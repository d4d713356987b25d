// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <vector>

#include "solve/detail/amg_csr.h"
#include "solve/detail/cholmod_solver.h"

namespace meshmorph::detail {

/// Parameters of the smoothed-aggregation hierarchy.
struct AmgOptions {
  int block_size = 1;        ///< unknowns per node at the finest level (aggregated together)
  int coarse_size = 500;     ///< a level with at most this many unknowns is solved by Cholesky
  int max_levels = 12;
  double strength = 0.08;    ///< θ of ‖A_IJ‖ ≥ θ √(‖A_II‖‖A_JJ‖) at level 0, halved per level
  int smoother_degree = 2;   ///< Chebyshev polynomial degree of D₁⁻¹A (pre and post)
  double smoother_ratio = 10.0;  ///< the Chebyshev interval is [1/ratio, 1] for D₁⁻¹A (ℓ1 diagonal)
  int power_iterations = 12;     ///< of the estimate of ρ(D⁻¹A) that smooths the prolongators
  int threads = 1;
};

/// Smoothed-aggregation algebraic multigrid (Vaněk, Mandel, Brezina 1996) used as a
/// symmetric positive definite preconditioner: one V-cycle with Chebyshev smoothing.
class AmgHierarchy {
 public:
  explicit AmgHierarchy(const AmgOptions& options) : options_(options) {}
  /// Builds the levels for `A` (symmetric, both triangles; read through the view, so its
  /// arrays must stay alive and unchanged while apply() is used). False when A is found not
  /// positive definite (a diagonal entry ≤ 0, or a Cholesky pivot ≤ 0 of the coarsest
  /// Galerkin operator).
  bool setup(const SparseView& A);
  /// Makes `P` (rows of A × coarse unknowns, in whole blocks of block_size per coarse node)
  /// the prolongator from the first coarse level, kept as it is (not smoothed), at every
  /// later setup(); aggregation starts below it. For high-order Lagrange spaces the vertex
  /// hats: their Galerkin operator PᵀAP has the linear mesh's pattern, where aggregating A
  /// itself would give the smoothed prolongator the pattern of A² (dense rows). An empty P
  /// goes back to aggregating A.
  void set_first_prolongator(Csr P);
  /// Makes a new matrix of the finest level's pattern the finest operator, keeping the coarse
  /// levels built for the old one (a cheaper, slightly weaker preconditioner). False when A
  /// has a diagonal entry ≤ 0 or there is no hierarchy of its size.
  bool rebind(const SparseView& A);
  /// rebind(), then the coarse operators of A through the prolongators of the last setup():
  /// A_{l+1} = R_l A_l P_l, products of known patterns (values only), and the coarsest
  /// factor. A new Newton matrix keeps most of what a setup() gives it (on the §5.2 shells
  /// half the CG iterations of rebind()) at a fraction of its cost: no aggregation, no
  /// smoothing of P, no symbolic products. False as rebind(), or when a coarse operator is
  /// found not positive definite.
  bool refresh(const SparseView& A);
  /// z = M⁻¹ r, one V-cycle from a zero initial guess (z and r must not alias).
  void apply(const double* r, double* z);
  /// y = A x with the finest operator as it is now (its values may have changed in place).
  void apply_operator(const double* x, double* y) const;

  int n_levels() const { return static_cast<int>(levels_.size()); }
  int rows(int level) const { return levels_[level].A.n; }
  std::int64_t nnz(int level) const { return levels_[level].A.nnz(); }
  /// Σ nnz(A_l) / nnz(A_0).
  double operator_complexity() const;

 private:
  struct Level {
    SparseView A;    // the operator (level 0: the caller's matrix; else `own`)
    Csr own;
    Csr P, R;        // prolongator to this level from the next, and its transpose
    int product_block = 1;  // block of A, P and R where all three have block rows, else 1
    std::vector<int> ap_blocks;  // blocks per row of A P (galerkin), for the refreshes
    std::vector<double> inv_diag;  // 1 / a_ii
    std::vector<double> inv_l1;    // 1 / Σ_j |a_ij|, the smoother's diagonal
    int block = 1;
    int row_block = 1;  // `block` where A has block rows (has_block_rows), else 1
    std::vector<double> x, b, r, d;
  };
  // Block rows, inverse diagonal and ℓ1 diagonal (false if a diagonal entry is ≤ 0), work vectors.
  bool prepare_level(Level& L);
  static int product_block(const Level& L);  // Level::product_block of a level with P and R built
  void residual_of(Level& L) const;  // L.r = L.b − A L.x
  bool build_level(std::size_t l, std::vector<double>& weights);
  void build_given_level(std::vector<double>& weights);  // level 1 through first_
  void smooth(Level& L, bool zero_guess);
  void cycle(std::size_t l);

  AmgOptions options_;
  Csr first_;      // set_first_prolongator's P (no columns: none)
  std::size_t given_ = 0;  // 1 when the hierarchy's first coarse level came through first_
  std::vector<Level> levels_;
  CholmodSolver coarse_;
};

/// Aggregates of the nodes of A (nodes are blocks of `block` unknowns), by strength of
/// connection ‖A_IJ‖_F ≥ θ √(‖A_II‖_F ‖A_JJ‖_F): a node and its strong neighbours form an
/// aggregate where none of them is taken, leftovers join a neighbouring aggregate, the rest
/// form new ones. Returns the aggregate of each node; `n_aggregates` is set.
std::vector<int> aggregate_nodes(const SparseView& A, int block, double theta, int threads, int& n_aggregates);

}  // namespace meshmorph::detail
