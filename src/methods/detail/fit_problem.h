// SPDX-License-Identifier: MIT
#pragma once
#include <array>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "meshmorph/energy/assembler.h"
#include "meshmorph/methods/fit.h"
#include "meshmorph/solve/newton.h"

namespace meshmorph {

/// Paper 003 eq. 8 as a NewtonProblem: F(x) = Σ_E ∫_{E_t} μ(A W⁻¹) + w_σ Σ_terms Σ_{s∈S} σ(x_s)².
/// The penalty's gradient is 2w σ ∇σ and its Hessian 2w(∇σ∇σᵀ + σ∇²σ) on the d×d block of
/// each fitted node (eq. 16 with nodal basis functions; its SPD projection in Projected
/// mode). admissible() applies the line-search rules of §2.2 and §3.4: det A > 0 at every
/// validity sample, min det A > det_floor · its initial value (eq. 15), |∇F| and max |σ|
/// grown by less than `growth` (eq. 14); F itself only decreases (Armijo).
///
/// Sliding (optimize): the nodes of each `slides` entry stay on its zero level set (a node
/// in two entries on their intersection; all its DOFs must be free). With N an orthonormal
/// basis of the constraint normals ∇σ_i at a slide node and P = I − N Nᵀ, the gradient there
/// is P g, the Hessian's rows and columns of the node are multiplied by P, and its diagonal
/// block gets c N Nᵀ (c its mean tangential diagonal, so the normal step is exactly 0) plus
/// the constraint curvature −Σ λ_i P ∇²σ_i P with g = Σ λ_i ∇σ_i + P g (the Hessian of the
/// Lagrangian on the tangent space; PSD-clamped in Projected mode). Trial points are
/// projected back onto the constraints by Gauss–Newton (minimal-norm corrections). A node on
/// one level set takes N and its share of |∇F| from it (step_normals, stationarity): ∇σ and
/// |P g| but at the creases of a facet surface (geometry/facet_surface.h).
///
/// Matrix-free (evaluate_action(), for newton_matrix_free()): the metric Hessian as an
/// operator (EnergyAssembler::prepare_hessian), slides applied as above to its action
/// (P H P v plus the diagonal blocks' additions), without fitted nodes (throws
/// std::invalid_argument otherwise). Constructed with `matrix_free`, the problem holds no
/// sparse pattern and evaluate() throws.
template <int d>
class FitProblem final : public MatrixFreeNewtonProblem {
 public:
  FitProblem(const Mesh& mesh, const Topology& topology, const std::vector<FitTerm>& terms,
             const std::vector<std::uint8_t>& fixed, const FitOptions& options, const Eigen::MatrixXd& x,
             const std::vector<FitTerm>& slides = {}, bool matrix_free = false);

  std::size_t n_free() const { return dofs_.n_free(); }
  const DofMap& dofs() const { return dofs_; }
  const Eigen::MatrixXd& state() const { return x_; }
  double weight = 1.0;  ///< w_σ

  /// max |σ(x_s)| over every term's nodes at x.
  double fit_error(const Eigen::MatrixXd& x) const;
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
  double energy() const { return assembler_->value(*metric_, x_, {}, options_.threads) + penalty_value(x_); }
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
  void add_penalty(const Eigen::MatrixXd& x, Want want, HessianMode mode, Assembly& out);
  // |∇F| over the free DOFs; `metric` gets the metric term's value and gradient at x.
  double gradient_norm(const Eigen::MatrixXd& x, Assembly& metric);
  double penalty_value(const Eigen::MatrixXd& x) const;
  void bind_blocks(const Eigen::SparseMatrix<double>& H);
  std::vector<std::int64_t> node_blocks(const Eigen::SparseMatrix<double>& H, const std::vector<std::int32_t>& nodes) const;
  // Slide constraints of one node: the level sets it lies on (1 or 2, < d).
  struct SlideNode {
    std::int32_t node = 0, first = 0;  // node, reduced index of its first DOF
    int m = 0;
    std::array<const LevelSetFunction*, 2> sigma{};
  };
  static Eigen::Matrix<double, d, Eigen::Dynamic> orthonormal(Eigen::Matrix<double, d, Eigen::Dynamic> N);  // of span N
  Eigen::Matrix<double, d, Eigen::Dynamic> normals(const SlideNode& s, const Eigen::MatrixXd& x) const;
  bool project_slides(Eigen::MatrixXd& x) const;  // false when a node cannot be projected
  // A slide node's step constraints: N (the normals that bind its step), P = I − N Nᵀ and
  // the addition to its diagonal block K + c N Nᵀ (constraint curvature, normal stiffness),
  // from its unconstrained diagonal block B and gradient g at the current iterate.
  struct SlideFrame {
    Eigen::Matrix<double, d, Eigen::Dynamic> N;
    Eigen::Matrix<double, d, d> P, add;
  };
  SlideFrame slide_frame(const SlideNode& s, const Eigen::Matrix<double, d, d>& B, const Eigen::Matrix<double, d, 1>& g,
                         HessianMode mode) const;
  void constrain_hessian(HessianMode mode, Assembly& out);
  bool step_to(const Eigen::VectorXd& p, double alpha, Eigen::MatrixXd& out) const;

  // min det A of one cell at x; `all` includes its flat-edge samples.
  double cell_min_det(std::size_t block, std::size_t cell, const Eigen::MatrixXd& x, bool all) const;

  const Mesh* mesh_;
  const std::vector<FitTerm>* terms_;
  FitOptions options_;
  FlatEdges flat_;  // empty unless options.flat_edges
  TargetField<d> targets_;
  DofMap dofs_;
  std::unique_ptr<EnergyAssembler<d>> assembler_;
  std::unique_ptr<Metric<d>> metric_;
  HessianAction<d> action_;  // of the last evaluate_action()
  // The vertex hats vanishing at fixed DOFs (matrix-free without slides only; null otherwise
  // or where no coarse DOF is left).
  std::unique_ptr<CoarseSpace<d>> coarse_;
  std::vector<double> node_blocks_;  // its node blocks (EnergyAssembler::hessian_blocks)
  std::vector<SlideFrame> frames_;   // of each slide node, at the last evaluate() or evaluate_action()
  Eigen::VectorXd slide_v_;          // apply_hessian's projected v
  // Offsets of the d×d diagonal block entries (k, l) of each fitted node (term by term) in
  // the Hessian's value array, −1 for a fixed DOF.
  std::vector<std::int64_t> block_offsets_;
  std::vector<LevelSetFunction> slide_sigma_;
  std::vector<SlideNode> slides_;
  std::vector<std::int32_t> slide_of_row_;  // reduced index of a slide node's first DOF → slot, else −1
  std::vector<std::int64_t> slide_offsets_;  // the d×d diagonal block of each slide node, as block_offsets_
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
