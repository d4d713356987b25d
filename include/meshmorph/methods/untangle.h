// SPDX-License-Identifier: MIT
#pragma once
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "meshmorph/energy/level_set_penalty.h"
#include "meshmorph/methods/boundary_targets.h"
#include "meshmorph/mesh/topology.h"
#include "meshmorph/solve/linear_solver.h"

namespace meshmorph {

/// The element the functional of paper 001 treats as ideal (eq. 6–9).
enum class UntangleReference {
  /// The input element (eq. 8, "reference element" compensation): a valid input is a minimiser,
  /// and its grading and anisotropy are kept. Needs a valid input mesh.
  Input,
  /// The regular simplex (square, cube), one size for the whole mesh (the input's mean cell
  /// volume): the paper's tests. Elements are driven towards equilateral shape.
  Regular,
  /// The input element for the valid cells (Bernstein bounds), the regular one for the
  /// others: a repair that keeps the valid cells as they are where it can.
  InputWhereValid,
};

/// How δ is lowered while the mesh is tangled (docs/untangle.md).
enum class DeltaRule {
  /// Newton converges (loosely) at each δ before the decrease of eq. 13–14 (with Δx = 0):
  /// the safeguard of DESIGN §6, which untangles cases the literal rule does not.
  Continuation,
  /// The paper's rule: δ decreases by eq. 13–14 after every Newton step of unit length.
  Paper,
};

/// Parameters of simultaneous untangling and smoothing (paper 001); defaults are the paper's
/// (§5: n = −1, α = 1, β = 0.1, ε_q = 0.01, h*_min = 0.75, ε_δ = 1e-6, γ = 0.5 / 1).
struct UntangleOptions {
  double n = -1.0;             ///< exponent of F = Σ_e q_e*ⁿ (eq. 2, 11)
  double h_min = 0.75;         ///< h*_min = h(V_min)/δ of the initial δ (eq. 24)
  double eps_delta = 1e-6;     ///< ε_δ: smallest initial δ
  double alpha = 1.0;          ///< eq. 14
  double beta = 0.1;           ///< eq. 14: δ never drops below β·δ in one update
  double eps_q = 0.01;         ///< stop when valid and |Δq_min|/q_min < ε_q
  double gamma_untangle = 0.5; ///< off-diagonal relaxation while tangled
  double gamma_smooth = 1.0;   ///< ... and while smoothing (δ = 0)
  UntangleReference reference = UntangleReference::Input;
  DeltaRule delta_rule = DeltaRule::Continuation;
  bool predictor = true;       ///< differential predictor between steps (eq. 22–23)
  int max_newton = 300;        ///< Newton steps per step of a time series
  /// End valid by the Bernstein bounds of det A, not only at the functional's points
  /// (docs/untangle.md, What is guaranteed for curved cells): smoothing keeps the bounds'
  /// validity, and folds between the points are sampled and untangled (8 rounds at most).
  /// Off: the points alone decide, and the caller checks the bounds. The untangle command and
  /// untangle_locally set it.
  bool certify = false;
  LinearSolverKind solver = LinearSolverKind::Auto;
  int threads = 0;
};

/// One Newton step of the report's history.
struct UntangleIteration {
  int step = 1;
  int newton = 0;         ///< Newton steps so far in this step (0: the starting mesh)
  double delta = 0.0;     ///< δ of the functional the step minimised
  double alpha = 0.0;     ///< the step length (0 for the starting row)
  double min_quality = 0.0;   ///< q_min = min_e q_e of eq. 3 at δ = 0 (0 when inverted)
  std::size_t inverted = 0;   ///< inverted cells after the step
};

struct UntangleResult {
  bool converged = false;
  std::string message;
  std::size_t initial_inverted = 0;  ///< inverted cells once the boundary is at its targets
  long long newton = 0, linear = 0, delta_updates = 0;
  double min_quality = 0.0;          ///< q_min at the end
  std::vector<UntangleIteration> history;
};

/// Simultaneous untangling and smoothing of paper 001: puts the prescribed nodes at their
/// targets (which may tangle the mesh) and minimises F = Σ_e q_e*ⁿ over the free nodes, with
/// the regularized volume h(V) while the mesh is tangled and F itself once it is valid.
/// Fixed and prescribed nodes are not unknowns; a slide node moves along its plane, held on
/// it by SlideConstraints (energy/slide_constraints.h; any plane), and a node of `surfaces`
/// moves along that level set (the input's own boundary facets, untangle_surfaces, or a
/// level set of the case), whatever its role in `bc`.
///
/// One Untangler serves a time series: each solve() starts from the previous result, moved
/// by the differential predictor (eq. 22–23) when it is on.
class Untangler {
 public:
  /// `input`, `topology` and `bc` must outlive the Untangler. Throws InputError when the
  /// reference is Input and an input cell is inverted.
  Untangler(const Mesh& input, const Topology& topology, const BoundaryTargets& bc, UntangleOptions options,
            const std::vector<FitTerm>& surfaces = {});
  ~Untangler();
  Untangler(const Untangler&) = delete;
  Untangler& operator=(const Untangler&) = delete;

  /// Moves `x` (dim × n_nodes; the input coordinates for the first step, else the last
  /// result) so that the Prescribed nodes sit at `target` (dim × n_nodes) and the mesh is
  /// valid and smooth. On return `x` is the last iterate, valid or not (see converged).
  UntangleResult solve(const Eigen::MatrixXd& target, Eigen::MatrixXd& x, int step = 1);

  struct Impl;  ///< the implementation for one dimension (src/methods/untangle.cpp)

 private:
  std::unique_ptr<Impl> impl_;
};

/// The surfaces that the boundary nodes flagged in `may_slide` (one flag per node) move on
/// while untangling: the boundary facets `facets` (indices into topology.facets; all of
/// topology.boundary_facets for the whole mesh) as they are, in smooth patches, as optimize's
/// `--boundary slide` makes them (boundary_slides, curved, patches split where the normals
/// turn by more than `feature_angle` degrees). A node of one patch slides on it, a node of
/// two on their common curve; corners, crease nodes and every node not flagged stay fixed.
std::vector<FitTerm> untangle_surfaces(const Mesh& mesh, const Topology& topology, const std::vector<std::int32_t>& facets,
                                       const std::vector<std::uint8_t>& may_slide, double feature_angle);

/// Inverted cells of `mesh` (Bernstein bounds of det A) whose corner nodes are all fixed,
/// prescribed or sliding in `bc`: only interior nodes of the cell (edge, face and body nodes)
/// can move, which rarely suffices when the cell was bent against a curved boundary, so
/// untangling should move the boundary along itself.
/// `invalid`, where given, flags the inverted cells of `mesh` (invalid_cells) instead of testing them again.
std::size_t boundary_bound_inverted(const Mesh& mesh, const BoundaryTargets& bc,
                                    const std::vector<std::uint8_t>* invalid = nullptr);

/// The result of untangle_locally and the cells of its patch.
struct LocalUntangle {
  UntangleResult result;
  std::size_t cells = 0;
  double deviation = 0.0;  ///< the largest distance of a sliding node from its surface
};

/// Repairs `x` (d × n, positions of the nodes of `mesh`) in a patch around its inverted cells
/// (Bernstein bounds): the inverted cells and `layers` rings of cells around them (sharing a
/// node), untangled as a mesh of their own (Untangler, reference InputWhereValid) with the nodes they
/// share with the rest of the mesh fixed, its boundary nodes flagged in `may_slide` sliding on
/// the patch's boundary facets (untangle_surfaces) and its other boundary nodes fixed. Nothing
/// outside the patch moves. x holds the patch's last iterate on return, valid or not
/// (result.converged).
/// `invalid`, where given, flags the inverted cells of x (invalid_cells) instead of testing them again.
LocalUntangle untangle_locally(const Mesh& mesh, const Topology& topology, const std::vector<std::uint8_t>& may_slide,
                               double feature_angle, int layers, UntangleOptions options, Eigen::MatrixXd& x,
                               const std::vector<std::uint8_t>* invalid = nullptr);

}  // namespace meshmorph
