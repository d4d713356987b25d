// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "meshmorph/mesh/topology.h"

namespace meshmorph {

/// Parameters of the stabilized Eikonal solve (paper 004, eq. 3.7).
struct EikonalOptions {
  /// Stabilization h of eq. 3.7 as a multiple of the mean node spacing of the mesh (cell
  /// size / order); the paper asks only for "a small parameter". h → 0 with the mesh.
  double h_factor = 1.0;
  double tolerance = 1e-10;  ///< Newton stops when max |Δε| ≤ tolerance · (mesh diameter)
  int max_newton = 40;       ///< Newton steps per continuation stage
  int threads = 0;           ///< OpenMP threads for assembly; 0 = the OpenMP default
};

struct EikonalResult {
  Eigen::VectorXd distance;  ///< ε per node (0 on the zero set; nodes in no cell: 0)
  double h = 0.0;            ///< the stabilization used
  int newton = 0;            ///< Newton steps over all stages
  int stages = 0;            ///< Newton solves at fixed h (continuation stages, or 1 from `start`)
  bool converged = false;
  std::string message;
};

/// Distance to a boundary part by the stabilized Eikonal equation −h Δε + |∇ε|² = 1 in Ω,
/// ε = 0 on `zero_nodes`, ∂ε/∂n = 0 on the rest of ∂Ω (natural), discretized with the
/// Lagrange basis of each cell block (orders 1 and 2 and up, isoparametric) on the mesh as
/// it is, and solved by Newton's method. Weak form: ∫ h ∇ε·∇w + (|∇ε|² − 1) w = 0.
///
/// The sign of the h term is the vanishing-viscosity one: with it ε ≥ 0 is the travel time
/// from the zero set and converges to the distance as h → 0 (eq. 3.7 as printed, +hΔε,
/// has −distance as its viscosity limit; docs/deform.md). Newton starts from the Poisson
/// solution at h = mesh diameter, and h is divided by 100 stage by stage to its target, each
/// stage converged by Newton with a backtracking line search on the residual norm (loosely,
/// to 1e-4 of the diameter, before the last).
///
/// `start` (one value per node, e.g. the solution on the mesh before its last deformation):
/// Newton starts from it at the target h, without the continuation, which it falls back to
/// when that does not converge. Empty: the continuation.
///
/// Throws InputError when `zero_nodes` is empty or a cell has det J ≤ 0.
EikonalResult eikonal_distance(const Mesh& mesh, const Topology& topology, const std::vector<std::int32_t>& zero_nodes,
                               const EikonalOptions& options = {}, const Eigen::VectorXd& start = {});

}  // namespace meshmorph
