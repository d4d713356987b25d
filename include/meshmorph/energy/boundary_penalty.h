// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "meshmorph/energy/assembler.h"
#include "meshmorph/mesh/topology.h"

namespace meshmorph {

/// The 1/h-weighted boundary mass matrix of paper 000 eq. 6 in the mesh's own order:
/// M_ab = Σ_f (1/h_f) ∫_f N_a N_b dΓ over the boundary facets f of the input mesh, with
/// h_f the in-radius of the cell of f (d·V/S: the cell's volume over its straight facet
/// areas — exact for simplices, a size measure for quads and hexes).
struct BoundaryMass {
  std::vector<std::int32_t> nodes;  ///< boundary nodes of every order, sorted
  Eigen::SparseMatrix<double> M;    ///< nodes.size() square, symmetric, in `nodes` order
};

/// Builds M from the coordinates `x` (usually the input mesh's).
BoundaryMass boundary_mass(const Mesh& mesh, const Topology& topology, const Eigen::MatrixXd& x);

/// The boundary term of the augmented Lagrangian (paper 000 eq. 5–6, 8):
///   E_b(x) = −Σ_ab M_ab λ_a·r_b + ½ μ Σ_ab M_ab r_a·r_b,  r_a = x_a − g_a,
/// over the prescribed nodes a (slide nodes are held by energy/slide_constraints.h, not
/// here). Nodal multipliers λ_a (d-vectors,
/// the nodal values of the P^p multiplier field). Nodes outside the constrained set are
/// either free or hard-fixed at their target, where r = 0, so their rows of M drop out.
template <int d>
class BoundaryPenalty {
 public:
  /// `nodes`: the prescribed nodes (sorted, all in mass.nodes).
  BoundaryPenalty(const BoundaryMass& mass, std::vector<std::int32_t> nodes);

  std::size_t size() const { return nodes_.size(); }
  const std::vector<std::int32_t>& nodes() const { return nodes_; }

  /// Targets g (d × size()), multipliers λ (d × size(), start at 0) and penalty μ.
  void set_target(const Eigen::MatrixXd& g) { g_ = g; }
  const Eigen::MatrixXd& target() const { return g_; }
  Eigen::MatrixXd& multipliers() { return lambda_; }
  const Eigen::MatrixXd& multipliers() const { return lambda_; }
  double mu = 1.0;

  /// r (d × size()) at the nodal coordinates x (d × n_nodes).
  Eigen::MatrixXd residual(const Eigen::MatrixXd& x) const;
  /// E_b(x).
  double value(const Eigen::MatrixXd& x) const;
  /// Adds E_b and, as `want` asks, its gradient and Hessian (μ M_ab P_a P_b) to an Assembly
  /// of `assembler` (same DofMap, Hessian in its pattern: every pair of constrained nodes on
  /// one facet shares a cell, so no entry is new).
  void add_to(const EnergyAssembler<d>& assembler, const Eigen::MatrixXd& x, Want want, Assembly& out);
  /// ‖r‖_M / ‖1‖_M: the constraint norm of paper 000 in the 1/h inner product, normalized to a
  /// length (an average distance of the nodes from their targets).
  double constraint_norm(const Eigen::MatrixXd& x) const;
  /// max_a |r_a|.
  double max_error(const Eigen::MatrixXd& x) const;
  /// Multiplier update (eq. 8): λ ← λ − μ r(x).
  void update_multipliers(const Eigen::MatrixXd& x) { lambda_ -= mu * residual(x); }
  /// Mean of the diagonal of M over the constrained nodes (to scale μ₀).
  double mean_diagonal() const;

 private:
  std::vector<std::int32_t> nodes_;
  Eigen::SparseMatrix<double> M_;  // restricted to nodes_
  double total_ = 0.0;             // 1ᵀ M 1
  Eigen::MatrixXd g_, lambda_;
  // Offsets of the Hessian entries (a, k; b, l) in the assembler's CSC value array, in the
  // order of M's nonzeros × d × d; -1 for fixed DOFs. Built on first use.
  std::vector<std::int64_t> hessian_offsets_;
  const EnergyAssembler<d>* bound_ = nullptr;  // the assembler whose pattern the offsets index
  void bind(const EnergyAssembler<d>& assembler, const Eigen::SparseMatrix<double>& H);
};

}  // namespace meshmorph
