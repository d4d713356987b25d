// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "meshmorph/energy/dof_map.h"
#include "meshmorph/energy/target.h"
#include "meshmorph/mesh/mesh.h"

namespace meshmorph {

/// The vertex space of a mesh as the coarse level of a two-level preconditioner for the
/// Hessian of EnergyAssembler: per cell corner and component, the linear (simplices) or
/// multilinear (quadrilaterals, hexahedra) hat function of that vertex, interpolated at every
/// node (it is in the span of every Lagrange basis). A coarse DOF is kept only where its hat
/// vanishes at every fixed DOF of its component, so that R, the hats' values at the free
/// DOFs, spans exact finite-element functions and Rᵀ H R is H's Galerkin restriction, which
/// EnergyAssembler::coarse_hessian forms cell by cell without H. Built once per mesh and
/// DofMap; on a 3D P3 mesh it has about 1/27 of the fine unknowns.
template <int d>
class CoarseSpace {
 public:
  /// `targets` gives each block's quadrature points (its table), where the hats' gradients
  /// are tabulated for the cells whose Hessian is held per point.
  CoarseSpace(const Mesh& mesh, const DofMap& dofs, const TargetField<d>& targets);

  /// n_free × size(): the hats at the free DOFs (reduced numbering), column-major.
  const Eigen::SparseMatrix<double>& R() const { return R_; }
  Eigen::Index size() const { return R_.cols(); }

  /// Per cell block: corners per cell (the first nodes of a cell, DESIGN's orderings); the
  /// corners' hat values at the cell's nodes (n × corners); their reference gradients at the
  /// block's quadrature points (corners × d, point after point).
  struct Block {
    int corners = 0;
    Eigen::MatrixXd values;
    std::vector<Eigen::MatrixXd> gradients;
  };
  const Block& block(std::size_t b) const { return blocks_[b]; }
  /// Rᵀ H R's pattern (full symmetric storage, values 0), and per block and cell the offset
  /// in its value array of each pair (i, j) of the cell's local coarse DOFs v·d + k (i
  /// fastest; −1 where either is not kept).
  const Eigen::SparseMatrix<double>& pattern() const { return pattern_; }
  const std::int32_t* scatter(std::size_t b, std::size_t c) const {
    const auto m = static_cast<std::size_t>(d * blocks_[b].corners);
    return scatter_[b].data() + c * m * m;
  }
  /// Coarse DOF of (block b, cell c, corner v, component k), −1 where it is not kept.
  std::int32_t dof(std::size_t b, std::size_t c, int v, int k) const {
    return cell_dofs_[b][(c * static_cast<std::size_t>(blocks_[b].corners) + static_cast<std::size_t>(v)) * d +
                         static_cast<std::size_t>(k)];
  }

 private:
  std::vector<Block> blocks_;
  std::vector<std::vector<std::int32_t>> cell_dofs_;
  Eigen::SparseMatrix<double> R_, pattern_;
  std::vector<std::vector<std::int32_t>> scatter_;
};

/// The same hats as a prolongator for the iterative linear solver's first coarse level
/// (LinearSolver::set_coarse_space): n_free × d·(kept vertices), each vertex's d components
/// consecutive. A vertex is kept only where its hat vanishes at every fixed DOF of every
/// component, so that its coarse unknowns form a whole block as the solver's aggregation
/// needs. Built without quadrature tables: all a Hessian's matrix is needed for.
template <int d>
Eigen::SparseMatrix<double> vertex_hats(const Mesh& mesh, const DofMap& dofs);

}  // namespace meshmorph
