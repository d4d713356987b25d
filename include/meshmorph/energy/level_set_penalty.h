// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "meshmorph/energy/assembler.h"
#include "meshmorph/energy/dof_map.h"
#include "meshmorph/geometry/level_set_function.h"

namespace meshmorph {

/// Nodes to be fitted to the zero level set of one function (paper 003 eq. 8: the set S), or
/// held on it (SlideConstraints).
struct FitTerm {
  LevelSetFunction sigma;
  std::vector<std::int32_t> nodes;  ///< sorted, unique
};

/// max |σ(x_s)| over the nodes of every term at x (d × n_nodes): their distance from their
/// surfaces (paper 003 eq. 14's fit error); 0 without nodes.
double fit_error(const std::vector<FitTerm>& terms, const Eigen::MatrixXd& x);

/// The level-set penalty of paper 003 eq. 8: F_σ(x) = w_σ Σ_terms Σ_{s∈S} σ(x_s)². Its
/// gradient at a fitted node is 2w σ ∇σ and its Hessian the d×d diagonal block
/// 2w(∇σ∇σᵀ + σ∇²σ) (eq. 16 with nodal basis functions), projected onto the PSD cone
/// (quality/spd_projection.h) in HessianMode::Projected. Only the free DOFs of `dofs` take
/// part. w_σ is `weight`; its adaptation (eq. 13) is the method's (methods/fit.h).
template <int d>
class LevelSetPenalty {
 public:
  /// Keeps references to `terms` and `dofs`, which must outlive the penalty.
  LevelSetPenalty(const std::vector<FitTerm>& terms, const DofMap& dofs) : terms_(&terms), dofs_(&dofs) {}

  double weight = 1.0;  ///< w_σ
  const std::vector<FitTerm>& terms() const { return *terms_; }

  /// fit_error(terms(), x).
  double max_error(const Eigen::MatrixXd& x) const { return fit_error(*terms_, x); }
  /// F_σ(x).
  double value(const Eigen::MatrixXd& x) const;
  /// Adds F_σ and, as `want` asks, its gradient and Hessian to an Assembly over the free DOFs
  /// of `dofs` (Hessian in an assembler's pattern, which holds every node's diagonal block;
  /// the offsets are found on the first call and kept, so one penalty serves one pattern).
  void add_to(const Eigen::MatrixXd& x, Want want, HessianMode mode, Assembly& out);
  /// The mean of `diagonal` (over the free DOFs) at the free DOFs of the fitted nodes; 1
  /// when there are none or the mean is not positive (the scale of w_σ's start, eq. 16).
  double mean_at_nodes(const Eigen::VectorXd& diagonal) const;
  /// One flag per node of a mesh with `n_nodes` nodes: 1 at a fitted node.
  std::vector<std::uint8_t> fitted(std::size_t n_nodes) const;

 private:
  const std::vector<FitTerm>* terms_;
  const DofMap* dofs_;
  // Offsets of the d×d diagonal block of each fitted node (term by term) in the Hessian's
  // value array (block_offsets.h).
  std::vector<std::int64_t> block_offsets_;
};

}  // namespace meshmorph
