// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "meshmorph/energy/coarse_space.h"
#include "meshmorph/energy/dof_map.h"
#include "meshmorph/energy/element_energy.h"
#include "meshmorph/energy/hessian_action.h"
#include "meshmorph/energy/target.h"
#include "meshmorph/mesh/topology.h"

namespace meshmorph {

/// What EnergyAssembler::assemble fills besides the value.
struct AssemblyOptions {
  Want want = Want::Hessian;                     ///< Value, + gradient, + Hessian
  HessianMode hessian = HessianMode::Projected;  ///< PSD projection of d²μ/dT² per point
  /// Per-cell weights ω_e (global cell order, blocks concatenated; paper 000 eq. 10–11);
  /// empty means ω_e = 1. E = Σ_e ω_e E_e.
  std::span<const double> weights;
  int threads = 0;  ///< OpenMP threads; 0 = omp_get_max_threads()
};

/// Result of an assembly over the free DOFs of a DofMap.
struct Assembly {
  double value = 0.0;              ///< Σ ω_e E_e; +∞ when any element is +∞ (inverted)
  Eigen::VectorXd gradient;        ///< n_free, reduced numbering (DofMap)
  /// n_free × n_free, column-major, full symmetric storage (both triangles), the pattern of
  /// EnergyAssembler (fixed across calls: only the values are rewritten).
  Eigen::SparseMatrix<double> hessian;
  std::vector<double> element_values;  ///< E_e per cell without ω_e (global cell order)
};

/// Assembles the energy Σ_e ω_e E_e of a metric over all cells of a mesh, with its gradient
/// and sparse Hessian over the free DOFs of a DofMap.
///
/// Built once per mesh: the sparsity pattern of the reduced Hessian (d×d node blocks from
/// Topology::node_nodes, fixed DOFs removed), a scatter map (cell, local a, local b) → offset
/// in the CSC value array, and the cells of each block grouped into patches of neighbours,
/// greedily coloured such that no two patches of one colour share a node. The element loop
/// runs colour by colour, the patches of a colour in parallel and the cells of a patch in
/// order, and writes gradient and Hessian without atomics; every entry receives its
/// contributions in the same order for any thread count, so results are bit-for-bit identical
/// across thread counts. Linear simplices take a fixed-size element kernel.
template <int d>
class EnergyAssembler {
 public:
  /// `mesh`, `topology` (of mesh), `targets` (of mesh) and `dofs` must outlive the assembler.
  /// `matrix` false skips the sparse pattern and scatter map (the bulk of the assembler's
  /// memory on high-order meshes): for the matrix-free Hessian only, and assemble() with
  /// Want::Hessian throws std::invalid_argument.
  EnergyAssembler(const Mesh& mesh, const Topology& topology, const TargetField<d>& targets,
                  const DofMap& dofs, bool matrix = true);

  /// Evaluates at nodal coordinates `x` (d × n_nodes; fixed DOFs are read from it too).
  /// Reuses the storage of `out` (its Hessian keeps this assembler's pattern). Want::Value
  /// sets `value` only; Gradient also `gradient` and `element_values`; Hessian also `hessian`.
  /// When the value is +∞ the derivatives are unspecified.
  void assemble(const Metric<d>& metric, const Eigen::MatrixXd& x, const AssemblyOptions& options,
                Assembly& out) const;

  /// The energy only (for line searches): Σ_e ω_e E_e, +∞ if any cell is inverted.
  double value(const Metric<d>& metric, const Eigen::MatrixXd& x, std::span<const double> weights = {},
               int threads = 0) const;

  /// Partial assembly of the Hessian of assemble() (weights ω_e = 1, `mode` as
  /// AssemblyOptions::hessian) at x into `out`. Returns false, leaving `out` unspecified, when
  /// μ is not finite at some point (an inverted cell).
  bool prepare_hessian(const Metric<d>& metric, const Eigen::MatrixXd& x, HessianMode mode, int threads,
                       HessianAction<d>& out) const;
  /// y = H v for the Hessian H over the free DOFs that `action` holds: the product of
  /// assemble()'s Hessian and v to rounding, element by element
  /// (y_e = Σ_q mat(K_q vec(V_e ∇N_q)) ∇N_qᵀ, by sum factorization on hexahedra; H_e v_e on
  /// simplices). The cells' y_e are stored in the action's scratch, then gathered node by node
  /// in cell order (one barrier, not one per colour), so y is bit-for-bit the same for any
  /// thread count. `v` and `y` have n_free entries.
  void apply_hessian(HessianAction<d>& action, const Eigen::VectorXd& v, Eigen::VectorXd& y, int threads = 0) const;
  /// The node blocks of that H, without forming H: for node a, entry (k, l) =
  /// Σ_e Σ_q Σ_jm ∂_j N_a K_q(k + dj, l + dm) ∂_m N_a (by sum factorization on hexahedra),
  /// d × d column-major at a·d², for every node (rows and columns of fixed DOFs included).
  /// Uses the action's scratch as apply_hessian() does.
  std::vector<double> hessian_blocks(HessianAction<d>& action, int threads = 0) const;
  /// The diagonal of that H over the free DOFs (of hessian_blocks()).
  Eigen::VectorXd hessian_diagonal(HessianAction<d>& action, int threads = 0) const;
  /// Rᵀ H R for that H and the coarse space's R (of this assembler's mesh and DofMap), formed
  /// cell by cell without H: Σ_q (∇N^c_q ⊗ I)ᵀ K_q (∇N^c_q ⊗ I) from the hats' gradients ∇N^c
  /// where H is held per point, R_eᵀ H_e R_e from the element matrices on simplices; full
  /// symmetric storage, exactly symmetric.
  Eigen::SparseMatrix<double> coarse_hessian(const HessianAction<d>& action, const CoarseSpace<d>& coarse,
                                             int threads = 0) const;

  const DofMap& dofs() const { return *dofs_; }
  std::size_t n_cells() const { return n_cells_; }
  /// Number of stored Hessian entries (both triangles).
  std::int64_t nnz() const { return outer_.empty() ? 0 : outer_.back(); }
  /// Number of patch colours of block i (parallel sweeps per assembly).
  int n_colors(std::size_t block) const { return static_cast<int>(blocks_[block].color_offset.size()) - 1; }

 private:
  struct BlockPlan {
    std::vector<std::int32_t> color_offset;  // colour k: patches color_offset[k] .. [k+1]
    std::vector<std::int32_t> patch_offset;  // patch p: cells order[patch_offset[p] .. [p+1])
    std::vector<std::int32_t> order;         // cells patch by patch, patches sorted by colour
    std::vector<std::int32_t> scatter;       // n_cells × n × n: offset of node a in column block of b
    std::int64_t first_slot = 0;             // slot of (cell 0, node 0): slots run over blocks, cells, nodes
  };
  // store(i, k, Σ over the slots s of node i of local[width·s + k]) for k < width: the gather
  // of per-cell products (slots of node i: node_slots_[node_slot_offset_[i] .. [i+1]), in
  // slot order whatever the threads). Defined in energy/detail/node_gather.h.
  template <class Store>
  void gather(const std::vector<double>& local, int width, int threads, Store store) const;
  const Mesh* mesh_;
  const Topology* topology_;
  const TargetField<d>* targets_;
  const DofMap* dofs_;
  std::size_t n_cells_ = 0;
  std::vector<BlockPlan> blocks_;
  // The reduced Hessian's CSC column pointers; a new Assembly::hessian gets its row indices
  // from the topology (detail::reduced_hessian_rows), not from a copy held here: at a million
  // nodes a copy is 0.6 GB.
  std::vector<int> outer_;
  std::vector<std::int64_t> node_slot_offset_, node_slots_;
};

}  // namespace meshmorph
