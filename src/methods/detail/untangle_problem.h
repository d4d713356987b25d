// SPDX-License-Identifier: MIT
#pragma once
#include <map>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "meshmorph/energy/assembler.h"
#include "meshmorph/energy/slide_constraints.h"
#include "meshmorph/mesh/topology.h"
#include "meshmorph/methods/boundary_targets.h"
#include "meshmorph/methods/untangle.h"
#include "meshmorph/quality/edge_quality.h"
#include "meshmorph/solve/newton.h"

namespace meshmorph {

/// The functional of paper 001, F(x) = Σ_e F_e with F_e the mean of q*(T)ⁿ over the points
/// of the cell (eq. 11; one point for a linear simplex, so F_e = q_e*ⁿ exactly), as a Newton
/// problem over the free DOFs, with δ and the off-diagonal relaxation γ as parameters.
///
/// Points: the one point of a linear simplex; the corners of a linear quadrilateral, where A
/// is the Jacobian of the corner triangle (docs/untangle.md: the mean over the corner
/// simplices in place of eq. 5's product); the points of the validity test (fem/validity.h)
/// for hexahedra and curved cells. So a finite F at δ = 0 means a valid mesh.
///
/// A slide node keeps its d DOFs as unknowns and is held on its plane by SlideConstraints
/// (energy/slide_constraints.h): its frame constrains the gradient and Hessian of every
/// evaluation and the predictor, and every trial and accepted point returns to the plane.
/// The nodes of `surfaces` are unknowns held on those level sets the same way, whatever
/// their role in `bc` (a node of two entries on their common curve).
template <int d>
class UntangleProblem final : public NewtonProblem {
 public:
  /// State measures at the current iterate.
  struct Measures {
    double v_min = 0.0;         ///< min over points of V = τ·V_reg (eq. 24's V_min)
    double q_min = 0.0;         ///< min over points of q (eq. 3, δ = 0; 0 where inverted)
    std::size_t inverted = 0;   ///< cells with det A ≤ 0 at a point (the validity test's points)
  };

  UntangleProblem(const Mesh& input, const Topology& topology, const BoundaryTargets& bc,
                  UntangleReference reference, double n, int threads, const std::vector<FitTerm>& surfaces = {});

  std::size_t n_free() const { return dofs_.n_free(); }
  const DofMap& dofs() const { return dofs_; }
  std::size_t n_cells() const { return n_cells_; }
  /// Sets the iterate, its slide nodes moved back onto their planes.
  void set_state(const Eigen::MatrixXd& x);
  const Eigen::MatrixXd& state() const { return x_; }
  double delta() const { return metric_.options().delta; }
  void set_delta(double delta) { metric_ = EdgeQuality<d>({delta, n_}); }
  void set_gamma(double gamma) { gamma_ = gamma; }
  /// With `certify`, a trial point where the Bernstein bounds find a cell folded
  /// (min_jacobian_det ≤ 0) has F = +∞: steps from a mesh valid by the bounds keep it so.
  void set_certify(bool certify) { certify_ = certify; }
  /// The accepted step of the last accept() (α p, reduced numbering).
  const Eigen::VectorXd& last_step() const { return last_step_; }

  /// F at the current iterate.
  double energy() const { return assembler_->value(metric_, x_, {}, threads_); }

  void evaluate(HessianMode mode, Assembly& out) override;
  double trial_value(const Eigen::VectorXd& p, double alpha) override;
  void accept(const Eigen::VectorXd& p, double alpha) override;

  Measures measure() const;
  /// Cells whose every node is fixed or prescribed and that are inverted: no motion of the
  /// free nodes can repair them.
  std::size_t stuck_inverted() const;
  /// Samples det A more finely where the points miss a fold: each cell that every point
  /// finds valid and whose Bernstein bounds find det A ≤ 0 between them gets the lattice of
  /// the piece where they found it (fold_samples) as points of its own, in F and in
  /// measure(), from now on (the input's Jacobian or the regular one as reference there, as
  /// at its other points). Returns the number of such cells: 0 means every cell valid at its
  /// points is valid by the bounds.
  std::size_t sample_folds(bool add = true);
  /// Δδ of eq. 13 at the current iterate for the step `dx` (reduced numbering; empty = 0):
  /// −(∂F/∂δ + ∂²F/∂δ∂x·dx) / ∂²F/∂δ².
  double delta_increment(const Eigen::VectorXd& dx) const;
  /// The differential predictor (eq. 22–23): the increment of the free nodes that keeps
  /// ∇F = 0 to first order when the prescribed nodes move from the current iterate to
  /// `target`, K_ii Δx_i = −K_ib Δx_b with the Hessian at the current iterate. Returns false
  /// (x unchanged) where the Hessian is not finite or the solve fails.
  bool predict(const Eigen::MatrixXd& target, LinearSolver& solver, Eigen::MatrixXd& increment);

 private:
  void scale_off_diagonal(Assembly& out) const;
  /// The targets, the assembler and all_fixed_ of the cells of mesh_.
  void build();
  /// Whether min_jacobian_det is > 0 on every cell at `x`.
  bool bounds_valid(const Eigen::MatrixXd& x) const;

  const Mesh* input_;
  const Mesh* mesh_;                // the input, or layout_ once cells are sampled at folds
  const Topology* input_topology_;
  const Topology* topology_;        // of mesh_
  const BoundaryTargets* bc_;
  UntangleReference reference_;
  int threads_;
  double n_;
  double mean_volume_ = 0.0;
  Mesh layout_;                     // the input's cells, those sampled at folds in blocks of their own
  Topology layout_topology_;
  std::vector<std::int32_t> cell_of_;  // layout cell → input cell (empty: the input's order)
  std::map<std::int32_t, Eigen::MatrixXd> fold_points_;  // input cell → its fold points (reference)
  std::vector<std::unique_ptr<ShapeTable>> fold_tables_;  // per layout block: its own table, or null
  double gamma_ = 1.0;
  bool certify_ = false;
  std::size_t n_cells_ = 0;
  std::vector<std::unique_ptr<ShapeTable>> corner_tables_;  // owned tables of the corner points
  TargetField<d> targets_;
  DofMap dofs_;                     // unknowns: free and slide nodes
  DofMap wide_dofs_;                // ... and the prescribed nodes (the predictor's K_ib)
  SlideConstraints<d> slides_;      // the slide nodes on their planes, over dofs_
  std::unique_ptr<EnergyAssembler<d>> assembler_, wide_assembler_;
  std::vector<int> component_;      // per reduced DOF: its coordinate k
  std::vector<std::uint8_t> all_fixed_;  // per cell (global order): no free DOF
  EdgeQuality<d> metric_;
  Eigen::MatrixXd x_, trial_;
  Eigen::VectorXd last_step_;
};

}  // namespace meshmorph
