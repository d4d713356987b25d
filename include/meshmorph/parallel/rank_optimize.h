// SPDX-License-Identifier: MIT
#pragma once
#include <Eigen/Core>

#include "meshmorph/methods/optimize.h"
#include "meshmorph/parallel/local_mesh.h"

namespace meshmorph {

/// Collective: TMOP mesh optimization (optimize_mesh's energy F = Σ_E ∫ μ(A W⁻¹)) of the mesh
/// that the ranks' local meshes make up, its DOFs fixed where LocalMesh::fixed says and no
/// sliding nodes. Each rank runs EnergyAssembler over its owned and ghost cells, which gives
/// it the whole gradient and Hessian rows of its owned DOFs; F (over owned cells), min det A
/// and |∇F| are summed or reduced over the ranks, and the rows go into a PETSc MPI matrix
/// solved by CG with GAMG (docs/parallel.md). The same bits for a fixed number of ranks. Newton with paper 003 §2.2's line-search
/// rules, every decision taken on the global figures: F decreases (Armijo), det A > 0 at every
/// validity sample of every rank's cells, |∇F| grows by less than options.growth. The steps
/// take the SPD-projected Hessian, and the exact one after a projected step was taken in
/// full, until a step of it fails. Stops at |∇F| ≤ rtol·|∇F₀| or a Newton decrement at
/// rounding level. `x` (d × local nodes, a valid start) holds the last accepted iterate on
/// return, the same at a node on every rank that holds it. The result is the same on every
/// rank; its `linear` counts CG iterations.
OptimizeResult optimize_on_ranks(const LocalMesh& local, const OptimizeOptions& options, Eigen::MatrixXd& x);

/// Collective: rank 0's options (`root`; nullptr on the other ranks) on every rank.
OptimizeOptions broadcast_optimize_options(const OptimizeOptions* root);

}  // namespace meshmorph
