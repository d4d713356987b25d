// SPDX-License-Identifier: MIT
#include "meshmorph/energy/assembler.h"

#include <algorithm>
#include <limits>
#include <string>

#include <omp.h>

#include "energy/detail/element_kernel.h"
#include "energy/detail/pattern.h"
#include "meshmorph/error.h"

namespace meshmorph {
namespace {

constexpr double k_inf = std::numeric_limits<double>::infinity();
// Cells per partial sum of the value. Fixed, so the summation order (chunk sums in cell order,
// then the chunks in order) and therefore the value are the same for every thread count.
constexpr std::size_t k_chunk = 1024;

int thread_count(int requested) { return requested > 0 ? requested : omp_get_max_threads(); }

double chunked_total(const std::vector<double>& chunk_sums) {
  double total = 0.0;
  for (double s : chunk_sums) total += s;
  return total;
}

template <int d>
void gather(const Eigen::MatrixXd& x, const std::int32_t* nodes, int n, detail::NodalMatrix<d>& X) {
  X.resize(d, n);
  for (int a = 0; a < n; ++a) X.col(a) = x.col(nodes[a]);
}

}  // namespace

template <int d>
EnergyAssembler<d>::EnergyAssembler(const Mesh& mesh, const Topology& topology, const TargetField<d>& targets,
                                    const DofMap& dofs)
    : mesh_(&mesh), targets_(&targets), dofs_(&dofs), n_cells_(mesh.n_cells()) {
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
  const detail::NodePattern pattern = detail::build_node_pattern(topology, dofs);
  detail::reduced_hessian_pattern(topology, dofs, pattern, outer_, inner_);
  blocks_.resize(mesh.cells.size());
  for (std::size_t bi = 0; bi < mesh.cells.size(); ++bi) {
    const CellBlock& block = mesh.cells[bi];
    BlockPlan& plan = blocks_[bi];
    detail::color_cells(block, topology, topology.block_offset[bi], plan.color_offset, plan.order);
    plan.scatter = detail::scatter_offsets(block, topology, pattern);
  }
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
  const auto n_free = static_cast<Eigen::Index>(dofs_->n_free());
  out.element_values.assign(n_cells_, 0.0);
  out.gradient.setZero(n_free);
  if (hess && (out.hessian.rows() != n_free || out.hessian.nonZeros() != nnz() || !out.hessian.isCompressed())) {
    out.hessian = Eigen::SparseMatrix<double>(n_free, n_free);
    out.hessian.resizeNonZeros(static_cast<Eigen::Index>(nnz()));
    std::copy(outer_.begin(), outer_.end(), out.hessian.outerIndexPtr());
    std::copy(inner_.begin(), inner_.end(), out.hessian.innerIndexPtr());
  }
  const int* colptr = hess ? out.hessian.outerIndexPtr() : nullptr;
  double* values = hess ? out.hessian.valuePtr() : nullptr;
  const std::int64_t nnz = hess ? out.hessian.nonZeros() : 0;
  const std::int32_t* red = dofs_->reduced_index().data();
  double* gradient = out.gradient.data();
  const std::span<const double> weights = options.weights;
#pragma omp parallel num_threads(thread_count(options.threads))
  {
    if (hess) {
#pragma omp for schedule(static)
      for (std::int64_t i = 0; i < nnz; ++i) values[i] = 0.0;
    }
    detail::ElementScratch<d> scratch;
    detail::NodalMatrix<d> X;
    std::size_t cell_base = 0;
    for (std::size_t bi = 0; bi < blocks_.size(); ++bi) {
      const CellBlock& block = mesh_->cells[bi];
      const BlockTargets<d>& bt = targets_->blocks[bi];
      const BlockPlan& plan = blocks_[bi];
      const int n = block.n_nodes_per_cell();
      for (std::size_t color = 0; color + 1 < plan.color_offset.size(); ++color) {
        // Cells of one colour share no node: their scatters never touch the same entry, so
        // which thread takes which cell does not matter and a dynamic schedule (which balances
        // threads slowed by other load on the machine) keeps the results bit-for-bit.
#pragma omp for schedule(dynamic, 64)
        for (std::int32_t i = plan.color_offset[color]; i < plan.color_offset[color + 1]; ++i) {
          const auto c = static_cast<std::size_t>(plan.order[static_cast<std::size_t>(i)]);
          const std::int32_t* nodes = block.cell(c);
          gather<d>(x, nodes, n, X);
          const double e = detail::element_kernel<d>(metric, *bt.table, bt.cell(c), X, options.want, options.hessian, scratch);
          out.element_values[cell_base + c] = e;
          if (!(e < k_inf)) continue;
          const double w = weights.empty() ? 1.0 : weights[cell_base + c];
          for (int a = 0; a < n; ++a)
            for (int k = 0; k < d; ++k) {
              const std::int32_t r = red[d * nodes[a] + k];
              if (r >= 0) gradient[r] += w * scratch.g(k, a);
            }
          if (!hess) continue;
          const std::int32_t* off = plan.scatter.data() + c * static_cast<std::size_t>(n * n);
          for (int b = 0; b < n; ++b)
            for (int l = 0; l < d; ++l) {
              const std::int32_t col = red[d * nodes[b] + l];
              if (col < 0) continue;
              double* column = values + colptr[col];
              const double* h = scratch.H.col(l * n + b).data();
              for (int a = 0; a < n; ++a) {
                double* target = column + off[a + n * b] - dofs_->first(static_cast<std::size_t>(nodes[a]));
                for (int k = 0; k < d; ++k) {
                  const std::int32_t r = red[d * nodes[a] + k];
                  if (r >= 0) target[r] += w * h[k * n + a];
                }
              }
            }
        }
      }
      cell_base += block.n_cells();
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
#pragma omp parallel num_threads(thread_count(threads)) reduction(| : infinite)
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
        gather<d>(x, block.cell(c), block.n_nodes_per_cell(), X);
        const BlockTargets<d>& bt = targets_->blocks[bi];
        const double e = detail::element_kernel<d>(metric, *bt.table, bt.cell(c), X, Want::Value, HessianMode::Exact, scratch);
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
