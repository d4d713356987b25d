// SPDX-License-Identifier: MIT
#pragma once
#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "meshmorph/methods/boundary_targets.h"
#include "meshmorph/mesh/topology.h"
#include "meshmorph/solve/linear_solver.h"

namespace meshmorph {

/// Parameters of the augmented-Lagrangian morph (paper 000 Algorithms 1 and 2). Defaults are
/// the paper's where it gives them; docs/morph.md explains the ones it leaves open.
struct MorphOptions {
  /// ε*: the run has converged when every prescribed node is within tolerance·L of its target
  /// (L = diagonal of the input mesh's bounding box) ...
  double tolerance = 1e-9;
  /// ... and the last Newton solve met δ* (½gᵀH⁻¹g ≤ δ*·E_ref, E_ref = Σ_e ω_e |e|: the
  /// energy of the identity map with the current weights).
  double gradient_tolerance = 1e-12;
  double eps0 = 0.1;       ///< ε₀ relative to the constraint norm at the start of a step
  double delta0 = 1e-3;    ///< δ₀, relative to E_ref like δ*
  /// μ₀ = penalty0 · (mean diagonal of the distortion Hessian at the constrained DOFs) /
  /// (mean diagonal of the boundary mass): the penalty starts `penalty0` times stiffer than
  /// the mesh next to it, whatever the units and the grading; μ = μ₀·(m/m₀)·(mean weight of
  /// the cells beside the constrained nodes).
  double penalty0 = 10.0;
  double m0 = 10.0;        ///< m₀ of Algorithm 1
  double m_factor = 100.0; ///< m ← m_factor·m when the constraint did not decrease enough
  /// After a multiplier update that leaves the boundary short of its targets, m grows by
  /// m_factor too unless c fell below min_decrease times its previous value: 0 (the default)
  /// raises μ after every such iteration, 1 only where c did not decrease (about Algorithm 1
  /// as printed). docs/morph.md, "Raising μ after multiplier updates".
  double min_decrease = 0.0;
  bool adaptive_weights = true;  ///< Algorithm 2; false keeps ω = 1 (paper §4.2 comparison)
  double alpha = 3.0;      ///< eq. 10
  double beta = 1.25;      ///< eq. 11
  /// Eq. 11's bound per update squared (up to β⁴) after an update that Newton absorbed in one
  /// step, and back by a square root (down to β) after one that took `weight_steps`; false:
  /// β at every update, as in the paper (docs/morph.md, "Weight growth").
  bool adaptive_growth = true;
  double max_weight = 1e12;  ///< upper bound on ω_e (docs/morph.md)
  int max_outer = 40;      ///< augmented-Lagrangian iterations per step
  /// Weight updates per augmented-Lagrangian iteration (Algorithm 2's loop) at most.
  int max_weight_updates = 100;
  /// Newton steps at most between two weight updates after the first solve of an AL
  /// iteration (which meets δ, as does the last); 0: every solve meets δ, as in the paper
  /// (docs/morph.md, "The weight loop").
  int weight_steps = 4;
  int max_newton = 200;    ///< Newton steps per nonlinear solve
  bool exact_first = true; ///< NewtonOptions::exact_first (DESIGN §6)
  /// Curved and tensor cells that block a line search join the energy at their validity
  /// samples; Ring guards every cell sharing a node with them too. Auto: Ring in 2D, Cells in
  /// 3D (docs/morph.md: a tetrahedron's ring is 30–60 cells).
  enum class Guard { Auto, Cells, Ring };
  Guard guard = Guard::Auto;
  /// When the augmented Lagrangian stalls short of the boundary (μ ≥ 1e12 μ₀ and the
  /// constraint no longer halves), finish with paper 001's untangling and smoothing from the
  /// stalled iterate, the prescribed nodes on their targets (DESIGN §6, docs/morph.md).
  bool finish_by_untangle = true;
  LinearSolverKind solver = LinearSolverKind::Auto;
  int threads = 0;
  /// Solve on the nodes in locality_order() (mesh/node_order.h); results come back in the
  /// input's numbering.
  bool renumber = true;
};

/// One augmented-Lagrangian iteration, for the report's history.
struct MorphIteration {
  int step = 1;
  int outer = 0;
  double constraint_norm = 0.0;     ///< ‖T(φ) − g‖ in the 1/h inner product, normalized (a length)
  double boundary_error_max = 0.0;  ///< max nodal distance from the targets
  double min_quality = 0.0;         ///< min_e 1/η_e (eq. 9) at the quadrature points
  double mu = 0.0;
  long long nonlinear = 0, newton = 0, linear = 0;  ///< cumulative counts
};

struct MorphResult {
  bool converged = false;
  std::string message;
  long long outer = 0, nonlinear = 0, newton = 0, linear = 0, krylov = 0;
  /// Cells whose distortion is also measured at their validity samples, so far in this
  /// Morpher's life: those that failed the dense validity test in a line search
  /// (energy/validity_guard.h).
  std::size_t guarded_cells = 0;
  std::vector<MorphIteration> history;
  /// Set when the augmented Lagrangian stalled and the untangle pass ran (finish_by_untangle):
  /// why it stalled, how far the boundary still was, and what the pass did. Its Newton steps
  /// and linear solves are in `newton` and `linear` too.
  struct Finish {
    std::string stall;                  ///< the augmented Lagrangian's message
    double boundary_error_max = 0.0;    ///< max nodal distance from the targets when it stalled
    std::size_t initial_inverted = 0;   ///< cells inverted once the boundary was placed
    long long newton = 0, linear = 0;
    bool valid = false;                 ///< the pass ended with a valid mesh
    std::string message;                ///< the pass's own
  };
  std::optional<Finish> finish;
};

/// Morphs a mesh by the augmented-Lagrangian method of paper 000: minimises
/// Σ_e ω_e ∫ η₀(A W⁻¹)² (W the input element's Jacobian) plus the boundary term of
/// BoundaryPenalty, raising μ and updating λ (Algorithm 1) and the weights ω_e (Algorithm 2)
/// until every prescribed node reaches its target. Fixed nodes are not unknowns.
///
/// One Morpher serves a whole time series: λ, μ and the weights are carried from one solve()
/// to the next (paper 000 §5.5), and quality is always measured against the input mesh.
class Morpher {
 public:
  /// `input` (its coordinates are the distortion targets), `topology` and `bc` must outlive
  /// the Morpher, except with MorphOptions::renumber (the default): it then solves on copies
  /// of its own in locality order and reads them only here. Throws InputError when the input
  /// mesh has an inverted element.
  Morpher(const Mesh& input, const Topology& topology, const BoundaryTargets& bc, MorphOptions options);
  ~Morpher();
  Morpher(const Morpher&) = delete;
  Morpher& operator=(const Morpher&) = delete;

  /// Moves `x` (dim × n_nodes, a valid mesh; the input coordinates for the first step) towards
  /// `target` (dim × n_nodes, read at Prescribed nodes; Slide nodes keep their plane through
  /// bc.target). `x` is always a valid mesh on return, also when the run does not converge.
  MorphResult solve(const Eigen::MatrixXd& target, Eigen::MatrixXd& x, int step = 1);

  struct Impl;  ///< the implementation for one dimension (src/methods/morph.cpp)
  struct Renumbered;  ///< the mesh in locality_order() (mesh/node_order.h), what Impl solves on

 private:
  std::unique_ptr<Renumbered> renumbered_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace meshmorph
