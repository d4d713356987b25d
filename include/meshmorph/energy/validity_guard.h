// SPDX-License-Identifier: MIT
#pragma once
#include <cstddef>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "meshmorph/energy/assembler.h"
#include "meshmorph/energy/dof_map.h"
#include "meshmorph/energy/target.h"
#include "meshmorph/mesh/mesh.h"

namespace meshmorph {

/// A metric's energy at the validity samples of chosen cells (fem/validity.h: the quadrature
/// points, the Lagrange nodes and the order-2p lattice), against the input's Jacobians there:
///
///   G(x) = Σ_{e guarded} ω_e Σ_s w_s μ(A_s W_s⁻¹),  w_s = |det W_s| · |reference cell| / n_s,
///
/// the sample mean of μ times the cell's volume, so a guarded cell counts its distortion once
/// at its quadrature points (the energy proper) and once over its samples.
///
/// Why: a metric integrated at quadrature points sees det A only there. A curved cell can be
/// driven towards det A = 0 at a node while every quadrature point stays well inside, and a
/// Newton line search that also checks the dense validity test then stalls against a wall
/// the energy does not see (docs/morph.md, "Large motions of high-order meshes"). With the
/// cells that blocked a line search guarded, μ's barrier (+∞ at det A ≤ 0) stands at their
/// samples, and the energy itself keeps them valid. G is minimised by any similarity of the
/// input (μ = its minimum at every sample), so morph's exact affine motions stay exact.
template <int d>
class ValidityGuard {
 public:
  /// `input` (its coordinates give W) and `dofs` must outlive the guard.
  ValidityGuard(const Mesh& input, const DofMap& dofs);

  /// Guards these cells (global indices: blocks concatenated, as AssemblyOptions::weights);
  /// returns how many of them were not guarded yet.
  std::size_t add(std::span<const std::size_t> cells);
  std::size_t size() const { return cells_.size(); }
  bool empty() const { return cells_.empty(); }
  /// Whether a cell is guarded.
  bool contains(std::size_t cell) const { return cell < guarded_.size() && guarded_[cell]; }

  /// G at nodal coordinates x (d × n_nodes), ω_e from `weights` (empty: 1); +∞ when a guarded
  /// cell has det A ≤ 0 (or μ = +∞) at a sample.
  double value(const Metric<d>& metric, const Eigen::MatrixXd& x, std::span<const double> weights) const;
  /// Adds G and, as `want` asks, its gradient and Hessian (in `mode`) over the free DOFs to
  /// `out`, whose Hessian must hold the pattern of an EnergyAssembler on the same DofMap (every
  /// pair of DOFs of one cell is in it).
  void add_to(const Metric<d>& metric, const Eigen::MatrixXd& x, std::span<const double> weights, Want want,
              HessianMode mode, Assembly& out) const;

 private:
  struct Cell {
    std::size_t index;     // global
    std::size_t block;     // into mesh.cells
    std::size_t local;     // cell within its block
    std::vector<QuadratureTarget<d>> samples;  // per validity sample; weight 0 where W is singular
  };
  Eigen::Matrix<double, d, Eigen::Dynamic> coordinates(const Cell& c, const Eigen::MatrixXd& x) const;

  const Mesh* mesh_;
  const DofMap* dofs_;
  std::vector<std::size_t> block_first_;  // global index of each block's first cell
  std::vector<Cell> cells_;
  std::vector<bool> guarded_;
};

}  // namespace meshmorph
