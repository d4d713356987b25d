// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "meshmorph/energy/target.h"
#include "meshmorph/methods/fit.h"
#include "meshmorph/mesh/topology.h"
#include "meshmorph/solve/linear_solver.h"

namespace meshmorph {

/// How optimize solves for its Newton steps.
enum class OptimizeSolver {
  /// MatrixFree in 3D, Cholesky in 2D: on every 3D mesh of MFEM's comparison the matrix-free
  /// steps took less time and memory, from 5.9k DOFs up (bench/README.md); on the 2D ones
  /// (≤ 4.2k DOFs) CHOLMOD took a third of the time.
  Auto,
  Cholesky,    ///< the assembled Hessian factored by CHOLMOD
  Iterative,   ///< the assembled Hessian, CG with smoothed-aggregation AMG
  PetscGamg,   ///< the assembled Hessian, PETSc's CG with GAMG (LinearSolverKind::PetscGamg)
  PetscHypre,  ///< the assembled Hessian, PETSc's CG with hypre BoomerAMG
  /// No matrix: the Hessian's action per quadrature point, CG preconditioned by its node
  /// blocks to an Eisenstat–Walker tolerance (newton_matrix_free; MFEM's partial assembly).
  MatrixFree,
};

/// Parameters of TMOP mesh optimization (paper 003 §2.2); defaults are those of MFEM's
/// mesh-optimizer runs of docs/optimize.md.
struct OptimizeOptions {
  std::string metric;            ///< "" = mu2 in 2D, mu303 in 3D (eq. 17)
  TargetKind target = TargetKind::Ideal;
  /// Gauss–Lobatto points on tensor cells (MFEM's -qt 1), degree 2p + 1 (p + 2 points per
  /// direction): they include the corners and edges, where the barrier of μ must act on
  /// curved cells (interior Gauss points alone let det A reach 0 at a corner). Simplices
  /// keep their symmetric rules (degree 2p).
  QuadratureFamily quadrature = QuadratureFamily::Lobatto;
  /// 0: 4p + 5 in 2D (p the mesh's highest order); in 3D 2p + 2 with simplices of order ≥ 3,
  /// else 2p + 1 on tensor cells and 2p on simplices. More points put the μ barrier where det
  /// A of curved cells dips between them (docs/optimize.md).
  int quadrature_degree = 0;
  int max_newton = 50;           ///< Newton steps at most (MFEM -ni)
  double rtol = 1e-10;           ///< stop at |∇F| ≤ rtol·|∇F₀| (MFEM -rtol)
  double growth = 1.2;           ///< line search: |∇F| grows by less than this (§2.2)
  /// min det A stays above det_floor · its initial value; 0: det A > 0 only, as TMOP (the
  /// barrier of μ keeps elements from collapsing; a floor would stall meshes that must thin one)
  double det_floor = 0.0;
  OptimizeSolver solver = OptimizeSolver::Auto;
  int threads = 0;  ///< OpenMP threads; 0 = optimize_threads(0, DOFs)
};

/// The OpenMP threads for a problem of `n_dofs` unknowns when `threads` are asked for: those,
/// or for 0, one thread below 30 000 DOFs (where the barriers of the coloured element loops
/// cost more than a second thread saves, many times more on a loaded machine) and the OpenMP
/// default above.
int optimize_threads(int threads, std::size_t n_dofs);

/// The quadrature degree of OptimizeOptions::quadrature_degree = 0 on `mesh` (0: each
/// block's metric_quadrature_degree): 4p + 5 in 2D, 2p + 2 in 3D with simplices of order
/// p ≥ 3, else 0, p the mesh's highest order.
int optimize_quadrature_degree(const Mesh& mesh);

/// One Newton step of the report's history.
struct OptimizeIteration {
  int newton = 0;
  double alpha = 0.0;          ///< step length (0 for the starting row)
  double energy = 0.0;         ///< F = Σ_E ∫ μ after the step
  double gradient_norm = 0.0;  ///< |∇F| over the free DOFs
  double min_det = 0.0;        ///< min det A over the validity samples
};

struct OptimizeResult {
  bool converged = false;
  std::string message;
  long long newton = 0, linear = 0;  ///< linear: solves, or CG iterations when matrix-free
  double energy0 = 0.0, energy = 0.0;  ///< F before and after
  double min_det0 = 0.0, min_det = 0.0;
  double mu_min = 0.0, mu_mean = 0.0, mu_max = 0.0;  ///< over the quadrature points, after
  int quadrature_degree = 0;  ///< the degree used (0: each block's metric_quadrature_degree)
  std::string solver;         ///< "cholmod", "cg-amg" or "matrix-free": what solved the steps
  std::vector<OptimizeIteration> history;
};

/// TMOP mesh optimization: minimises F = Σ_E ∫_{E_t} μ(A W⁻¹) over the DOFs not flagged in
/// `fixed` (one flag per DOF, dim·node + k) from `x` (d × n, a valid mesh), by Newton with
/// the line-search rules of paper 003 §2.2 (det A > 0 at every validity sample, F decreases,
/// |∇F| grows by less than `growth`). The nodes of each `slides` entry move on the zero
/// level set of its function (a node in two entries on their intersection curve): each
/// Newton step is restricted to the tangent space there, and trial points are projected
/// back onto the surface. Converged when |∇F| ≤ rtol·|∇F₀| or the Newton decrement is at
/// rounding level. `x` is the last accepted iterate on return (always valid).
OptimizeResult optimize_mesh(const Mesh& mesh, const Topology& topology, const std::vector<std::uint8_t>& fixed,
                             const std::vector<FitTerm>& slides, const OptimizeOptions& options, Eigen::MatrixXd& x);

/// Sliding constraints for boundary facets `facets` (indices into topology.facets; all of
/// topology.boundary_facets for `--boundary slide`), on the input's own geometry. The facets
/// form smooth patches: neighbours (across a corner edge in 3D, a corner in 2D) join when
/// their outward normals at the joint differ by at most `feature_angle` degrees. A patch
/// whose facets all lie on one plane (to 1e-10 of the mesh's size) slides on that plane;
/// any other on its discrete surface, the union of its facets' polynomial maps frozen at
/// mesh.x (geometry/facet_surface.h). A node of one patch slides on it, a node of two (3D,
/// a feature curve) on both, so on their common curve, and every other node of the facets
/// (corners, nodes of 3+ patches, of a crease inside one patch, or of two patches tangent
/// there) is fixed. Sets the flags of those nodes in `fixed` (one per DOF: 0 for a sliding
/// node, 1 for a fixed one) and returns one entry per patch that holds a sliding node.
/// Without `curved` (`--boundary slide-planes`, MFEM's `-bnd`) only coplanar facets join and
/// the nodes of curved facets are fixed: nodes slide on planes and on the lines where two meet.
std::vector<FitTerm> boundary_slides(const Mesh& mesh, const Topology& topology, const std::vector<std::int32_t>& facets,
                                     double feature_angle, bool curved, std::vector<std::uint8_t>& fixed);

}  // namespace meshmorph
