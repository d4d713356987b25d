// SPDX-License-Identifier: MIT
#pragma once
#include <cstddef>
#include <vector>

namespace meshmorph {

struct TensorGrid;
template <int d>
class EnergyAssembler;

/// The Hessian of an energy as an operator (partial assembly): what EnergyAssembler's
/// apply_hessian(), hessian_blocks(), hessian_diagonal() and coarse_hessian() need, with no
/// matrix. Filled by EnergyAssembler::prepare_hessian and read only by it: for point q of a
/// cell, K_q = w_q (W_q⁻¹ ⊗ I) d²μ/dT²(T_q) (W_q⁻¹ ⊗ I)ᵀ (d² × d²; d²μ/dT² PSD-projected in
/// Projected mode), the second derivative of w_q μ with respect to the reference gradient
/// G = X ∇N_q of the nodal map (T = G W⁻¹, so vec(T) = (W⁻ᵀ ⊗ I) vec(G)); on simplices the
/// element Hessians instead, which are fewer numbers and flops. Both in single precision:
/// reading them bounds the product, and the action is then H's to ~1e-7 relative, which the
/// inexact Newton steps of newton_matrix_free absorb (value and gradient stay in double).
/// Holds scratch for the products: one product at a time per action.
template <int d>
class HessianAction {
 public:
  /// Whether the products of cell block `block` go by sum factorization (a hexahedral block
  /// whose rule is a tensor grid, ShapeTable::tensor).
  bool sum_factorized(std::size_t block) const { return tensor_[block] != nullptr; }
  /// Whether cell block `block` is held as element Hessians (simplices) rather than per point.
  bool element_matrices(std::size_t block) const { return !element_[block].empty(); }

 private:
  friend class EnergyAssembler<d>;
  // Layouts: energy/detail/hessian_kernels.h. Per cell block, the packed K_q of its points,
  // where the block is sum-factorized in batches of cells interleaved by SIMD lane.
  std::vector<std::vector<float>> K_;
  // Per cell block of simplices instead of K_: the packed element Hessians.
  std::vector<std::vector<float>> element_;
  // Per cell block: the 1D factors of a sum-factorized block's table, else null.
  std::vector<const TensorGrid*> tensor_;
  // The per-cell results of a product before they are gathered by node.
  std::vector<double> local_;
};

}  // namespace meshmorph
