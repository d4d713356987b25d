// SPDX-License-Identifier: MIT
#pragma once
#include <memory>
#include <vector>

#include "meshmorph/energy/coarse_space.h"
#include "meshmorph/energy/dof_map.h"
#include "meshmorph/mesh/mesh.h"
#include "meshmorph/solve/linear_solver.h"

namespace meshmorph::detail {

/// The coordinates of the nodes of the free DOFs, d per node in the order of the unknowns
/// (LinearSolverOptions::coordinates); empty when some node has only part of its DOFs free.
template <int d>
std::vector<double> free_node_coordinates(const Mesh& mesh, const DofMap& dofs) {
  std::vector<double> x;
  x.reserve(dofs.n_free());
  for (std::size_t j = 0; j < dofs.n_nodes(); ++j) {
    const std::int32_t free = dofs.first(j + 1) - dofs.first(j);
    if (free == 0) continue;
    if (free != d) return {};
    for (int k = 0; k < d; ++k) x.push_back(mesh.x(k, static_cast<Eigen::Index>(j)));
  }
  return x;
}

/// The linear solver of a method's Newton steps on the free DOFs of `mesh` (d unknowns per
/// node), given the nodes' coordinates (for PETSc's GAMG). On high-order meshes the iterative
/// backend gets the vertex hats as its first coarse level (LinearSolver::set_coarse_space):
/// aggregating their dense Hessian rows directly costs minutes of set-up.
template <int d>
std::unique_ptr<LinearSolver> make_newton_solver(LinearSolverKind kind, int threads, const Mesh& mesh,
                                                 const DofMap& dofs) {
  LinearSolverOptions lo;
  lo.kind = kind;
  lo.block_size = d;
  lo.dim = d;
  lo.cell_nodes = mesh.max_cell_nodes();
  lo.threads = threads;
  lo.coordinates = free_node_coordinates<d>(mesh, dofs);
  std::unique_ptr<LinearSolver> solver = make_linear_solver(lo, dofs.n_free());
  if (mesh.order() > 1 && resolve_linear_solver(kind, d, dofs.n_free(), lo.cell_nodes) == LinearSolverKind::Iterative)
    solver->set_coarse_space(vertex_hats<d>(mesh, dofs));
  return solver;
}

}  // namespace meshmorph::detail
