// SPDX-License-Identifier: MIT
#include "meshmorph/energy/assembler.h"

#include <algorithm>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>

#include "energy/detail/element_kernel.h"
#include "energy/detail/pattern.h"
#include "meshmorph/error.h"
#include "meshmorph/threads.h"

namespace meshmorph {
namespace {

constexpr double k_inf = std::numeric_limits<double>::infinity();
// Cells per partial sum of the value. Fixed, so the summation order (chunk sums in cell order,
// then the chunks in order) and therefore the value are the same for every thread count.
constexpr std::size_t k_chunk = 1024;
// Cells per patch of the element sweep (detail::patch_cells). A patch's Hessian entries stay in
// cache while its cells are scattered one after another; the patches must still be many per
// colour for the threads to share them.
constexpr int k_patch_size = 64;

double chunked_total(const std::vector<double>& chunk_sums) {
  double total = 0.0;
  for (double s : chunk_sums) total += s;
  return total;
}

// The element kernel for N nodes per cell: fixed-size for linear simplices (N = d + 1), the
// general kernel for N = Eigen::Dynamic.
template <int d, int N>
struct Kernel {
  static constexpr bool fixed = N != Eigen::Dynamic;
  using Nodal = std::conditional_t<fixed, Eigen::Matrix<double, d, N>, detail::NodalMatrix<d>>;
  using Scratch = std::conditional_t<fixed, detail::FixedElementScratch<d, N>, detail::ElementScratch<d>>;

  static double eval(const Metric<d>& metric, const BlockTargets<d>& bt, std::size_t c, const Eigen::MatrixXd& x,
                     const std::int32_t* nodes, int n, Want want, HessianMode mode, Nodal& X, Scratch& s) {
    if constexpr (!fixed) X.resize(d, n);
    for (int a = 0; a < n; ++a) X.col(a) = x.col(nodes[a]);
    if constexpr (fixed)
      return detail::element_kernel_fixed<d, N>(metric, *bt.table, bt.cell(c), X, want, mode, s);
    else
      return detail::element_kernel<d>(metric, *bt.table, bt.cell(c), X, want, mode, s);
  }
};

// E_e of one cell of a block with n nodes per cell, through the kernel that assemble() uses
// for it, so that value() and assemble() agree bit for bit.
template <int d>
double cell_value(const Metric<d>& metric, const BlockTargets<d>& bt, std::size_t c, const Eigen::MatrixXd& x,
                  const std::int32_t* nodes, int n, detail::NodalMatrix<d>& X, detail::ElementScratch<d>& s) {
  if (n == d + 1) {
    typename Kernel<d, d + 1>::Nodal Xf;
    typename Kernel<d, d + 1>::Scratch unused;  // Want::Value fills nothing
    return Kernel<d, d + 1>::eval(metric, bt, c, x, nodes, n, Want::Value, HessianMode::Exact, Xf, unused);
  }
  return Kernel<d, Eigen::Dynamic>::eval(metric, bt, c, x, nodes, n, Want::Value, HessianMode::Exact, X, s);
}

}  // namespace

template <int d>
EnergyAssembler<d>::EnergyAssembler(const Mesh& mesh, const Topology& topology, const TargetField<d>& targets,
                                    const DofMap& dofs, bool matrix)
    : mesh_(&mesh), topology_(&topology), targets_(&targets), dofs_(&dofs), n_cells_(mesh.n_cells()) {
  MESHMORPH_CHECK(mesh.dim == d, "EnergyAssembler: the mesh dimension differs from d");
  MESHMORPH_CHECK(dofs.dim() == d && dofs.n_nodes() == mesh.n_nodes(), "EnergyAssembler: the DofMap does not fit the mesh");
  MESHMORPH_CHECK(targets.blocks.size() == mesh.cells.size(), "EnergyAssembler: the targets do not fit the mesh");
  MESHMORPH_CHECK(topology.node_node_offset.size() == mesh.n_nodes() + 1, "EnergyAssembler: the topology does not fit the mesh");
  for (std::size_t bi = 0; bi < mesh.cells.size(); ++bi) {
    MESHMORPH_CHECK(mesh.cells[bi].n_nodes_per_cell() <= detail::k_max_nodes, "EnergyAssembler: too many nodes per cell");
    MESHMORPH_CHECK(targets.blocks[bi].table && targets.blocks[bi].table->n_nodes() == mesh.cells[bi].n_nodes_per_cell() &&
                        targets.blocks[bi].points.size() ==
                            mesh.cells[bi].n_cells() * static_cast<std::size_t>(targets.blocks[bi].n_points()),
                    "EnergyAssembler: the targets do not fit cell block " + std::to_string(bi));
  }
  detail::NodePattern pattern;
  if (matrix) {
    pattern = detail::build_node_pattern(topology, dofs);
    detail::reduced_hessian_columns(dofs, pattern, outer_);
  }
  blocks_.resize(mesh.cells.size());
  for (std::size_t bi = 0; bi < mesh.cells.size(); ++bi) {
    const CellBlock& block = mesh.cells[bi];
    BlockPlan& plan = blocks_[bi];
    detail::CellPatches patches = detail::patch_cells(block, topology, topology.block_offset[bi], k_patch_size);
    plan.color_offset = std::move(patches.color_offset);
    plan.patch_offset = std::move(patches.patch_offset);
    plan.order = std::move(patches.order);
    if (matrix) plan.scatter = detail::scatter_offsets(block, topology, pattern);
  }
  // The slots of each node, in block, cell and local order (a counting sort).
  node_slot_offset_.assign(mesh.n_nodes() + 1, 0);
  std::int64_t slots = 0;
  for (std::size_t bi = 0; bi < mesh.cells.size(); ++bi) {
    blocks_[bi].first_slot = slots;
    slots += static_cast<std::int64_t>(mesh.cells[bi].nodes.size());
    for (std::int32_t node : mesh.cells[bi].nodes) ++node_slot_offset_[static_cast<std::size_t>(node) + 1];
  }
  for (std::size_t i = 0; i < mesh.n_nodes(); ++i) node_slot_offset_[i + 1] += node_slot_offset_[i];
  node_slots_.resize(static_cast<std::size_t>(slots));
  std::vector<std::int64_t> next(node_slot_offset_.begin(), node_slot_offset_.end() - 1);
  for (std::size_t bi = 0; bi < mesh.cells.size(); ++bi)
    for (std::size_t s = 0; s < mesh.cells[bi].nodes.size(); ++s)
      node_slots_[static_cast<std::size_t>(next[static_cast<std::size_t>(mesh.cells[bi].nodes[s])]++)] =
          blocks_[bi].first_slot + static_cast<std::int64_t>(s);
}

template <int d>
void EnergyAssembler<d>::assemble(const Metric<d>& metric, const Eigen::MatrixXd& x, const AssemblyOptions& options,
                                  Assembly& out) const {
  MESHMORPH_CHECK(x.rows() == d && static_cast<std::size_t>(x.cols()) == mesh_->n_nodes(),
                  "EnergyAssembler::assemble: x must be dim × n_nodes");
  MESHMORPH_CHECK(options.weights.empty() || options.weights.size() == n_cells_,
                  "EnergyAssembler::assemble: one weight per cell is needed");
  if (options.want == Want::Value) {
    out.value = value(metric, x, options.weights, options.threads);
    return;
  }
  const bool hess = options.want == Want::Hessian;
  MESHMORPH_CHECK(!hess || !outer_.empty(), "EnergyAssembler::assemble: built without a Hessian pattern (matrix-free)");
  const auto n_free = static_cast<Eigen::Index>(dofs_->n_free());
  out.element_values.assign(n_cells_, 0.0);
  out.gradient.setZero(n_free);
  if (hess && (out.hessian.rows() != n_free || out.hessian.nonZeros() != nnz() || !out.hessian.isCompressed())) {
    out.hessian = Eigen::SparseMatrix<double>(n_free, n_free);
    out.hessian.resizeNonZeros(static_cast<Eigen::Index>(nnz()));
    std::copy(outer_.begin(), outer_.end(), out.hessian.outerIndexPtr());
    detail::reduced_hessian_rows(*topology_, *dofs_, outer_.data(), out.hessian.innerIndexPtr());
  }
  const int* colptr = hess ? out.hessian.outerIndexPtr() : nullptr;
  double* values = hess ? out.hessian.valuePtr() : nullptr;
  const std::int64_t nnz = hess ? out.hessian.nonZeros() : 0;
  const std::int32_t* red = dofs_->reduced_index().data();
  double* gradient = out.gradient.data();
  const std::span<const double> weights = options.weights;
#pragma omp parallel num_threads(resolve_threads(options.threads))
  {
    if (hess) {
#pragma omp for schedule(static)
      for (std::int64_t i = 0; i < nnz; ++i) values[i] = 0.0;
    }
    std::size_t cell_base = 0;
    // Sweeps the cells of block bi, patch colour by patch colour, with the kernel for N nodes per cell.
    auto sweep = [&](std::size_t bi, auto nodes_per_cell) {
      constexpr int N = decltype(nodes_per_cell)::value;
      constexpr int max_dofs = d * (N == Eigen::Dynamic ? detail::k_max_nodes : N);
      using K = Kernel<d, N>;
      const CellBlock& block = mesh_->cells[bi];
      const BlockTargets<d>& bt = targets_->blocks[bi];
      const BlockPlan& plan = blocks_[bi];
      const int n = N == Eigen::Dynamic ? block.n_nodes_per_cell() : N;
      const int dn = d * n;
      typename K::Nodal X;
      typename K::Scratch scratch;
      for (std::size_t color = 0; color + 1 < plan.color_offset.size(); ++color) {
        // Patches of one colour share no node: their scatters never touch the same entry, so
        // which thread takes which patch does not matter and a dynamic schedule (which balances
        // threads slowed by other load on the machine) keeps the results bit-for-bit.
#pragma omp for schedule(dynamic, 1)
        for (std::int32_t p = plan.color_offset[color]; p < plan.color_offset[color + 1]; ++p) {
          for (std::int32_t i = plan.patch_offset[p]; i < plan.patch_offset[p + 1]; ++i) {
            const auto c = static_cast<std::size_t>(plan.order[static_cast<std::size_t>(i)]);
            const std::int32_t* nodes = block.cell(c);
            const double e = K::eval(metric, bt, c, x, nodes, n, options.want, options.hessian, X, scratch);
            out.element_values[cell_base + c] = e;
            if (!(e < k_inf)) continue;
            const double w = weights.empty() ? 1.0 : weights[cell_base + c];
            // Reduced index (−1 fixed) of local DOF d·a + k, and its rank among the free DOFs of
            // node a: the free DOFs of a node are consecutive, so that is its row offset within
            // the rows of node a in any column.
            std::int32_t dof[max_dofs], rank[max_dofs];
            for (int a = 0; a < n; ++a) {
              std::int32_t next = 0;
              for (int k = 0; k < d; ++k) {
                dof[d * a + k] = red[d * nodes[a] + k];
                rank[d * a + k] = dof[d * a + k] >= 0 ? next++ : -1;
              }
            }
            const double* g = scratch.g.data();  // d × n column-major
            for (int j = 0; j < dn; ++j)
              if (dof[j] >= 0) gradient[dof[j]] += w * g[j];
            if (!hess) continue;
            const std::int32_t* off = plan.scatter.data() + c * static_cast<std::size_t>(n * n);
            for (int b = 0; b < n; ++b)
              for (int l = 0; l < d; ++l) {
                const std::int32_t col = dof[d * b + l];
                if (col < 0) continue;
                double* column = values + colptr[col];
                const double* h = scratch.H.data() + static_cast<std::ptrdiff_t>(l * n + b) * dn;  // component-major
                for (int a = 0; a < n; ++a) {
                  double* target = column + off[a + n * b];
                  for (int k = 0; k < d; ++k)
                    if (rank[d * a + k] >= 0) target[rank[d * a + k]] += w * h[k * n + a];
                }
              }
          }
        }
      }
    };
    for (std::size_t bi = 0; bi < blocks_.size(); ++bi) {
      if (mesh_->cells[bi].n_nodes_per_cell() == d + 1)
        sweep(bi, std::integral_constant<int, d + 1>{});
      else
        sweep(bi, std::integral_constant<int, Eigen::Dynamic>{});
      cell_base += mesh_->cells[bi].n_cells();
    }
  }
  std::vector<double> chunk_sums((n_cells_ + k_chunk - 1) / k_chunk, 0.0);
  bool infinite = false;
  for (std::size_t g = 0; g < n_cells_; ++g) {
    const double e = out.element_values[g];
    if (!(e < k_inf)) infinite = true;
    chunk_sums[g / k_chunk] += (weights.empty() ? 1.0 : weights[g]) * e;
  }
  out.value = infinite ? k_inf : chunked_total(chunk_sums);
}

template <int d>
double EnergyAssembler<d>::value(const Metric<d>& metric, const Eigen::MatrixXd& x, std::span<const double> weights,
                                 int threads) const {
  MESHMORPH_CHECK(x.rows() == d && static_cast<std::size_t>(x.cols()) == mesh_->n_nodes(),
                  "EnergyAssembler::value: x must be dim × n_nodes");
  MESHMORPH_CHECK(weights.empty() || weights.size() == n_cells_, "EnergyAssembler::value: one weight per cell is needed");
  std::vector<std::size_t> block_end;
  for (const CellBlock& b : mesh_->cells) block_end.push_back((block_end.empty() ? 0 : block_end.back()) + b.n_cells());
  const auto n_chunks = static_cast<std::int64_t>((n_cells_ + k_chunk - 1) / k_chunk);
  std::vector<double> chunk_sums(static_cast<std::size_t>(n_chunks), 0.0);
  int infinite = 0;
#pragma omp parallel num_threads(resolve_threads(threads)) reduction(| : infinite)
  {
    detail::ElementScratch<d> scratch;
    detail::NodalMatrix<d> X;
#pragma omp for schedule(dynamic, 4)
    for (std::int64_t chunk = 0; chunk < n_chunks; ++chunk) {
      const std::size_t begin = static_cast<std::size_t>(chunk) * k_chunk;
      const std::size_t end = std::min(n_cells_, begin + k_chunk);
      std::size_t bi = static_cast<std::size_t>(std::upper_bound(block_end.begin(), block_end.end(), begin) - block_end.begin());
      double sum = 0.0;
      for (std::size_t g = begin; g < end; ++g) {
        while (g >= block_end[bi]) ++bi;
        const CellBlock& block = mesh_->cells[bi];
        const std::size_t c = g - (block_end[bi] - block.n_cells());
        const double e = cell_value<d>(metric, targets_->blocks[bi], c, x, block.cell(c), block.n_nodes_per_cell(), X, scratch);
        if (!(e < k_inf)) infinite = 1;
        sum += (weights.empty() ? 1.0 : weights[g]) * e;
      }
      chunk_sums[static_cast<std::size_t>(chunk)] = sum;
    }
  }
  return infinite ? k_inf : chunked_total(chunk_sums);
}

template class EnergyAssembler<2>;
template class EnergyAssembler<3>;

}  // namespace meshmorph
