// SPDX-License-Identifier: MIT
#pragma once
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "meshmorph/energy/assembler.h"
#include "meshmorph/energy/boundary_penalty.h"
#include "meshmorph/energy/slide_constraints.h"
#include "meshmorph/energy/validity_guard.h"
#include "meshmorph/methods/boundary_targets.h"
#include "meshmorph/solve/newton.h"

namespace meshmorph {

/// The augmented-Lagrangian functional of paper 000 (eq. 6–7) as a NewtonProblem: the
/// weighted distortion Σ_e ω_e ∫ η₀² against the input mesh plus the boundary term of the
/// Prescribed nodes, over the nodes that are not Fixed. Slide nodes stay on their planes
/// (through bc.target, normal bc.normal) by SlideConstraints (energy/slide_constraints.h):
/// gradient and Hessian constrained by their frames, so that Newton's decrement measures the
/// tangential gradient, and every trial and accepted point returned onto the planes. Holds
/// the current coordinates, slide nodes on their planes.
template <int d>
class MorphProblem final : public NewtonProblem {
 public:
  MorphProblem(const Mesh& input, const Topology& topology, const BoundaryTargets& bc, int threads);

  std::size_t n_free() const { return dofs_.n_free(); }
  const DofMap& dofs() const { return dofs_; }
  /// Moves the current coordinates to x, its slide nodes onto their planes.
  void set_state(const Eigen::MatrixXd& x);
  const Eigen::MatrixXd& state() const { return x_; }
  BoundaryPenalty<d>& penalty() { return *penalty_; }
  /// The penalty's targets from a full d × n target (read at the Prescribed nodes).
  Eigen::MatrixXd gather_targets(const Eigen::MatrixXd& target) const;

  /// Σ_e ω_e |e| over the input cells: the energy of the identity map with the current weights.
  double reference_energy() const { return reference_energy_; }
  /// Volume-weighted mean of ω_e over the cells that hold a constrained node: how much the
  /// weights have stiffened the mesh beside the boundary (1 with ω = 1).
  double boundary_weight() const { return boundary_weight_; }
  /// Diagonal of the input mesh's bounding box.
  double length_scale() const { return length_scale_; }
  /// Mean diagonal of the projected distortion Hessian at the free DOFs of the constrained
  /// nodes, at the current state (for μ₀).
  double distortion_stiffness();
  /// Algorithm 2, lines 4–8: ω_e ← min(β ω_e, max(ω_e, e^{α(η_e − 1)}), max_weight), never
  /// below ω_e. Returns whether any weight changed.
  bool update_weights(double alpha, double beta, double max_weight);
  /// Cells whose nodes are all Fixed or Prescribed and that are not valid with the prescribed
  /// nodes at `target` (d × n): no motion of the free nodes can repair them.
  std::size_t stuck_inverted(const Eigen::MatrixXd& target) const;
  /// min_e 1/η_e at the current state (eq. 9 on the quadrature points of each cell).
  double min_quality();

  void evaluate(HessianMode mode, Assembly& out) override;
  bool evaluate_gradient(Assembly& out) override;
  double trial_value(const Eigen::VectorXd& p, double alpha) override;
  bool admissible(const Eigen::VectorXd& p, double alpha) override;
  void accept(const Eigen::VectorXd& p, double alpha) override;
  /// Guards the cells that failed the dense validity test in the last line search (their
  /// distortion at the validity samples joins the energy, energy/validity_guard.h).
  bool refine() override;
  /// Number of guarded cells.
  std::size_t guarded_cells() const { return guard_.size(); }
  /// refine() also guards every cell that shares a node with a blocking one.
  void widen_guard() { widen_guard_ = true; }

 private:
  const std::vector<double>& distortions();  // η_e per cell at the current state (cached)
  void weights_changed();  // recomputes reference_energy_ and boundary_weight_
  // The energy's terms at x_ (distortion, guard, penalty), before the slide constraints.
  void assemble(Want want, HessianMode mode, Assembly& out);
  // out = x_ + α p, slide nodes returned onto their planes; false where one does not return.
  bool step_to(const Eigen::VectorXd& p, double alpha, Eigen::MatrixXd& out) const;
  const Mesh* mesh_;
  const Topology* topology_;
  const BoundaryTargets* bc_;
  int threads_;
  TargetField<d> targets_;
  DofMap dofs_;
  std::unique_ptr<EnergyAssembler<d>> assembler_;
  std::unique_ptr<Metric<d>> metric_;
  BoundaryMass mass_;
  std::unique_ptr<BoundaryPenalty<d>> penalty_;
  SlideConstraints<d> slides_;
  ValidityGuard<d> guard_;
  std::vector<std::size_t> blocking_;  // cells (global) that failed admissible() since the last refine()
  bool widen_guard_ = false;
  std::vector<double> weights_, volumes_;
  std::vector<std::uint32_t> boundary_cells_;  // cells with a constrained node
  double reference_energy_ = 0.0, boundary_weight_ = 1.0, length_scale_ = 1.0;
  bool dense_validity_ = false;  // curved or tensor cells: check validity beyond the quadrature points
  Eigen::MatrixXd x_, trial_;
  std::vector<double> eta_;     // distortions() of the state with version eta_version_
  long long version_ = 0, eta_version_ = -1;  // bumped by every change of x_
};

}  // namespace meshmorph
