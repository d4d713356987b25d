// SPDX-License-Identifier: MIT
#pragma once
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "meshmorph/mesh/topology.h"

namespace meshmorph {

/// The unknowns of an energy: which nodal degrees of freedom are free and their numbers in
/// the reduced system. DOFs are interleaved, dof = dim·node + k; the free ones are numbered
/// 0, 1, … in increasing dof order, so the free DOFs of one node are consecutive. Fixed DOFs
/// keep their values and are eliminated from the gradient and the Hessian.
class DofMap {
 public:
  DofMap() = default;
  /// Every DOF of `n_nodes` nodes in `dim` dimensions is free.
  static DofMap all_free(int dim, std::size_t n_nodes);
  /// All DOFs of the listed nodes are fixed (indices in [0, n_nodes); duplicates allowed).
  static DofMap fixing_nodes(int dim, std::size_t n_nodes, std::span<const std::int32_t> fixed_nodes);
  /// Any mask: `fixed[dof]` nonzero fixes that DOF (size dim·n_nodes).
  static DofMap from_mask(int dim, std::span<const std::uint8_t> fixed);
  /// The nodes of every order on the boundary facets of `mesh` are fixed (fem/trace.h).
  static DofMap fixing_boundary(const Mesh& mesh, const Topology& topology);

  int dim() const { return dim_; }
  std::size_t n_nodes() const { return first_.empty() ? 0 : first_.size() - 1; }
  std::size_t n_dofs() const { return reduced_.size(); }
  std::size_t n_free() const { return free_.size(); }
  bool is_free(std::size_t dof) const { return reduced_[dof] >= 0; }
  /// Reduced index of a DOF, −1 when it is fixed.
  std::int32_t reduced(std::size_t dof) const { return reduced_[dof]; }
  /// Reduced index of the first free DOF of `node` (= number of free DOFs before it);
  /// the node has free DOFs reduced [first(node), first(node + 1)).
  std::int32_t first(std::size_t node) const { return first_[node]; }
  /// Full DOF of each reduced index.
  const std::vector<std::int32_t>& free_dofs() const { return free_; }
  /// Reduced index per DOF (−1 fixed), the table behind reduced().
  const std::vector<std::int32_t>& reduced_index() const { return reduced_; }

  /// The free entries of a full DOF vector (size n_dofs(), e.g. vec of a dim × n matrix).
  Eigen::VectorXd restrict(const Eigen::Ref<const Eigen::VectorXd>& full) const;
  /// x(k, node) += alpha · step[reduced(dim·node + k)] for every free DOF; x is dim × n_nodes.
  void add_step(const Eigen::Ref<const Eigen::VectorXd>& step, double alpha, Eigen::MatrixXd& x) const;

 private:
  int dim_ = 0;
  std::vector<std::int32_t> reduced_;  // per dof
  std::vector<std::int32_t> first_;    // per node + 1
  std::vector<std::int32_t> free_;     // per free dof
};

}  // namespace meshmorph
