// SPDX-License-Identifier: MIT
#pragma once
#include <array>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "meshmorph/energy/assembler.h"
#include "meshmorph/energy/level_set_penalty.h"
#include "meshmorph/energy/slide_constraints.h"
#include "meshmorph/methods/fit.h"
#include "meshmorph/solve/newton.h"

namespace meshmorph {

/// Paper 003 eq. 8 as a NewtonProblem: F(x) = Σ_E ∫_{E_t} μ(A W⁻¹) + F_σ(x), the metric
/// integral plus the level-set penalty (energy/level_set_penalty.h). admissible() applies
/// the line-search rules of §2.2 and §3.4: det A > 0 at every validity sample, min det A >
/// det_floor · its initial value (eq. 15), |∇F| and max |σ| grown by less than `growth`
/// (eq. 14); F itself only decreases (Armijo).
///
/// Sliding (optimize): the nodes of each `slides` entry stay on its zero level set
/// (energy/slide_constraints.h: gradient, Hessian and |∇F| constrained by the nodes' frames,
/// trial points returned onto the level sets).
///
/// Matrix-free (evaluate_action(), for newton_matrix_free()): the metric Hessian as an
/// operator (EnergyAssembler::prepare_hessian), slides applied to its action (P H P v plus
/// the frames' additions), without fitted nodes (throws std::invalid_argument otherwise).
/// Constructed with `matrix_free`, the problem holds no sparse pattern and evaluate() throws.
template <int d>
class FitProblem final : public MatrixFreeNewtonProblem {
 public:
  FitProblem(const Mesh& mesh, const Topology& topology, const std::vector<FitTerm>& terms,
             const std::vector<std::uint8_t>& fixed, const FitOptions& options, const Eigen::MatrixXd& x,
             const std::vector<FitTerm>& slides = {}, bool matrix_free = false);

  std::size_t n_free() const { return dofs_.n_free(); }
  const DofMap& dofs() const { return dofs_; }
  const Eigen::MatrixXd& state() const { return x_; }
  /// The level-set penalty F_σ; its `weight` is w_σ.
  LevelSetPenalty<d>& penalty() { return penalty_; }

  /// max |σ(x_s)| over every term's nodes at x.
  double fit_error(const Eigen::MatrixXd& x) const { return penalty_.max_error(x); }
  double fit_error() const { return fit_error(x_); }
  /// min det A over the validity samples of every cell at x (without the flat-edge samples
  /// when options.flat_edges).
  double min_det(const Eigen::MatrixXd& x) const;
  /// Cells at x whose det A ≤ 0 at a validity sample, except on flat edges when
  /// options.flat_edges; and the cells whose det A ≤ 0 only on their flat edges.
  std::array<std::size_t, 2> invalid_cells(const Eigen::MatrixXd& x) const;
  double min_det() const { return min_det(x_); }
  /// Mean diagonal of the projected metric Hessian at the free DOFs of the fitted nodes.
  double metric_stiffness();
  /// Σ over every quadrature point of w_q |det W_q|: the measure of the target mesh, the
  /// scale of F's rounding error (μ + 1 is O(1) per point for the TMOP metrics).
  double target_measure() const;
  /// F at the current iterate.
  double energy() const { return assembler_->value(*metric_, x_, {}, options_.threads) + penalty_.value(x_); }
  /// Value and gradient norm of F at x (the line search's reference).
  void remember_current();
  /// |∇F| over the free DOFs at the iterate of the last remember_current().
  double current_gradient_norm() const { return gradient_norm_; }
  /// F and min det A at the iterate of the last accept(), as the line search measured them.
  double accepted_energy() const { return current_.energy; }
  double accepted_min_det() const { return current_.min_det; }
  /// min, mean and max of μ(T) over the metric quadrature points of every cell at the
  /// current iterate (+∞ where a point is inverted).
  std::array<double, 3> metric_range() const;

  void evaluate(HessianMode mode, Assembly& out) override;
  double trial_value(const Eigen::VectorXd& p, double alpha) override;
  bool admissible(const Eigen::VectorXd& p, double alpha) override;
  void accept(const Eigen::VectorXd& p, double alpha) override;
  void evaluate_action(HessianMode mode, Assembly& out) override;
  void apply_hessian(const Eigen::VectorXd& v, Eigen::VectorXd& y) override;
  HessianBlocks hessian_blocks() override;
  bool coarse_hessian(CoarseHessian& out) override;

 private:
  // |∇F| over the free DOFs; `metric` gets the metric term's value and gradient at x.
  double gradient_norm(const Eigen::MatrixXd& x, Assembly& metric);
  bool step_to(const Eigen::VectorXd& p, double alpha, Eigen::MatrixXd& out) const;

  // min det A of one cell at x; `all` includes its flat-edge samples.
  double cell_min_det(std::size_t block, std::size_t cell, const Eigen::MatrixXd& x, bool all) const;

  const Mesh* mesh_;
  FitOptions options_;
  FlatEdges flat_;  // empty unless options.flat_edges
  TargetField<d> targets_;
  DofMap dofs_;
  LevelSetPenalty<d> penalty_;
  SlideConstraints<d> slides_;
  std::unique_ptr<EnergyAssembler<d>> assembler_;
  std::unique_ptr<Metric<d>> metric_;
  HessianAction<d> action_;  // of the last evaluate_action()
  // The vertex hats vanishing at fixed DOFs (matrix-free without slides only; null otherwise
  // or where no coarse DOF is left).
  std::unique_ptr<CoarseSpace<d>> coarse_;
  std::vector<double> node_blocks_;  // its node blocks (EnergyAssembler::hessian_blocks)
  Eigen::VectorXd slide_v_;          // apply_hessian's tangential v
  // F, min det A and |∇F| at the point x + α p that trial_value() and admissible() measured
  // (admitted_, in trial_; `admitted` once admissible() passed it) and at the accepted one.
  struct Measured {
    double alpha = -1.0, energy = 0.0, min_det = 0.0, gradient_norm = 0.0;
    bool admitted = false;
  };
  Measured admitted_, current_;
  // The metric term's value and gradient at x_ (from remember_current() or accept(): what
  // evaluate_action() returns) and at trial_ (from admissible()).
  Assembly metric_at_current_, metric_at_trial_;
  double min_det0_ = 0.0;
  double gradient_norm_ = 0.0, error_ = 0.0;  // at the current iterate, for the line search
  Eigen::MatrixXd x_, trial_;
};

}  // namespace meshmorph
