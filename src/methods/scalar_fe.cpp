// SPDX-License-Identifier: MIT
#include "methods/detail/scalar_fe.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <Eigen/LU>

#include "energy/detail/pattern.h"
#include "meshmorph/error.h"
#include "meshmorph/threads.h"

namespace meshmorph::detail {
namespace {

// Below this many cells a block is assembled by one thread (see stiffness.cpp).
constexpr std::int64_t k_min_parallel_cells = 512;

// Exact for the products of two basis gradients and a basis function on affine simplices
// of order p (degree 3p − 2: one point for P1); tensor cells get degree 3p per variable.
int scalar_degree(ElementType type, int order) { return is_simplex(type) ? std::max(1, 3 * order - 2) : 3 * order; }

}  // namespace

ScalarAssembler::ScalarAssembler(const Mesh& mesh, const Topology& topology, int threads, std::string_view method)
    : n_nodes_(mesh.n_nodes()), threads_(resolve_threads(threads)) {
  const int d = mesh.dim;
  MESHMORPH_CHECK(topology.node_node_offset.size() == n_nodes_ + 1, std::string(method) + ": the topology does not fit the mesh");
  outer_.assign(topology.node_node_offset.begin(), topology.node_node_offset.end());
  inner_.assign(topology.node_nodes.begin(), topology.node_nodes.end());
  double size_sum = 0.0;
  std::size_t n_cells = 0;
  for (std::size_t bi = 0; bi < mesh.cells.size(); ++bi) {
    const CellBlock& block = mesh.cells[bi];
    MESHMORPH_CHECK(topological_dim(block.type) == d, std::string(method) + ": cell blocks must have the mesh's dimension");
    const ShapeTable& table = shape_table(block.type, block.order, scalar_degree(block.type, block.order));
    const int n = block.n_nodes_per_cell();
    const double simplex_factor = is_simplex(block.type) ? (d == 2 ? 2.0 : 6.0) : 1.0;
    Block& out = blocks_.emplace_back();
    out.cells.resize(block.n_cells());
    out.scatter.resize(block.n_cells() * static_cast<std::size_t>(n * n));
    for (std::size_t c = 0; c < block.n_cells(); ++c) {
      ScalarCell& cell = out.cells[c];
      cell.nodes = block.cell(c);
      cell.table = &table;
      cell.order = block.order;
      cell.G.resize(static_cast<std::size_t>(table.n_points()));
      cell.w.resize(table.n_points());
      Eigen::MatrixXd X(d, n);
      for (int a = 0; a < n; ++a) X.col(a) = mesh.x.col(cell.nodes[a]);
      for (int q = 0; q < table.n_points(); ++q) {
        const Eigen::MatrixXd A = X * table.grad(q);
        const double det = A.determinant();
        if (!(det > 0.0))
          throw InputError(std::string(method) + ": cell " + std::to_string(topology.block_offset[bi] + c) +
                           " (0-based, cell blocks concatenated) has det J <= 0 at a quadrature point; deform needs a valid "
                           "mesh to start from");
        cell.G[static_cast<std::size_t>(q)] = table.grad(q) * A.inverse();
        cell.w[q] = table.weights[q] * det;
      }
      cell.size = std::pow(simplex_factor * cell.w.sum(), 1.0 / d) / block.order;
      size_sum += cell.size;
      std::int32_t* off = out.scatter.data() + c * static_cast<std::size_t>(n * n);
      for (int b = 0; b < n; ++b) {
        const auto begin = topology.node_nodes.begin() + topology.node_node_offset[static_cast<std::size_t>(cell.nodes[b])];
        const auto end = topology.node_nodes.begin() + topology.node_node_offset[static_cast<std::size_t>(cell.nodes[b]) + 1];
        for (int a = 0; a < n; ++a) off[a + n * b] = static_cast<std::int32_t>(std::lower_bound(begin, end, cell.nodes[a]) - begin);
      }
    }
    n_cells += block.n_cells();
    color_cells(block, topology, topology.block_offset[bi], out.color_offset, out.order);
  }
  mean_size_ = n_cells ? size_sum / static_cast<double>(n_cells) : 1.0;
}

void ScalarAssembler::assemble(const ScalarKernel& kernel, Eigen::SparseMatrix<double>& A, Eigen::VectorXd& F) const {
  std::vector<double> values(inner_.size(), 0.0);
  F = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(n_nodes_));
  for (const Block& block : blocks_) {
    if (block.cells.empty()) continue;
    const int n = block.cells.front().table->n_nodes();
#pragma omp parallel num_threads(threads_) if (static_cast<std::int64_t>(block.cells.size()) >= k_min_parallel_cells)
    {
      Eigen::MatrixXd Ke(n, n);
      Eigen::VectorXd Fe(n);
      for (std::size_t color = 0; color + 1 < block.color_offset.size(); ++color) {
        // Cells of one colour share no node: no two threads write one entry, and each entry
        // sums its cells in colour order whatever the thread count.
#pragma omp for schedule(dynamic, 16)
        for (std::int32_t i = block.color_offset[color]; i < block.color_offset[color + 1]; ++i) {
          const auto c = static_cast<std::size_t>(block.order[static_cast<std::size_t>(i)]);
          const ScalarCell& cell = block.cells[c];
          Ke.setZero();
          Fe.setZero();
          kernel(cell, Ke, Fe);
          const std::int32_t* off = block.scatter.data() + c * static_cast<std::size_t>(n * n);
          for (int b = 0; b < n; ++b) {
            double* column = values.data() + outer_[static_cast<std::size_t>(cell.nodes[b])];
            for (int a = 0; a < n; ++a) column[off[a + n * b]] += Ke(a, b);
            F[cell.nodes[b]] += Fe[b];
          }
        }
      }
    }
  }
  const auto n = static_cast<Eigen::Index>(n_nodes_);
  A.resize(n, n);
  A.resizeNonZeros(static_cast<Eigen::Index>(inner_.size()));
  std::copy(outer_.begin(), outer_.end(), A.outerIndexPtr());
  std::copy(inner_.begin(), inner_.end(), A.innerIndexPtr());
  std::copy(values.begin(), values.end(), A.valuePtr());
}

DirichletSolver::DirichletSolver(std::vector<std::uint8_t> fixed) : fixed_(std::move(fixed)) {
  free_index_.assign(fixed_.size(), -1);
  for (std::size_t i = 0; i < fixed_.size(); ++i)
    if (!fixed_[i]) {
      free_index_[i] = static_cast<int>(free_nodes_.size());
      free_nodes_.push_back(static_cast<int>(i));
    }
}

bool DirichletSolver::factorize(const Eigen::SparseMatrix<double>& A) {
  // Split the columns into the free block A_ff and the coupling A_fd to the fixed nodes.
  const auto m = static_cast<Eigen::Index>(free_nodes_.size());
  std::vector<Eigen::Triplet<double>> ff, fd;
  ff.reserve(static_cast<std::size_t>(A.nonZeros()));
  for (Eigen::Index col = 0; col < A.outerSize(); ++col)
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, col); it; ++it) {
      const int r = free_index_[static_cast<std::size_t>(it.row())];
      if (r < 0) continue;
      const int cf = free_index_[static_cast<std::size_t>(col)];
      if (cf >= 0) ff.emplace_back(r, cf, it.value());
      else fd.emplace_back(r, static_cast<int>(col), it.value());
    }
  Eigen::SparseMatrix<double> A_ff(m, m);
  A_ff.setFromTriplets(ff.begin(), ff.end());
  A_fd_.resize(m, A.cols());
  A_fd_.setFromTriplets(fd.begin(), fd.end());
  if (m == 0) return true;
  if (!analyzed_) {
    lu_.analyzePattern(A_ff);
    analyzed_ = true;
  }
  lu_.factorize(A_ff);
  return lu_.info() == Eigen::Success;
}

Eigen::VectorXd DirichletSolver::free_part(const Eigen::VectorXd& full) const {
  Eigen::VectorXd out(static_cast<Eigen::Index>(free_nodes_.size()));
  for (std::size_t k = 0; k < free_nodes_.size(); ++k) out[static_cast<Eigen::Index>(k)] = full[free_nodes_[k]];
  return out;
}

void DirichletSolver::solve(const Eigen::VectorXd& b, Eigen::VectorXd& u) const {
  if (free_nodes_.empty()) return;
  Eigen::VectorXd u_d = u;
  for (int i : free_nodes_) u_d[i] = 0.0;
  const Eigen::VectorXd y = lu_.solve(free_part(b) - A_fd_ * u_d);
  for (std::size_t k = 0; k < free_nodes_.size(); ++k) u[free_nodes_[k]] = y[static_cast<Eigen::Index>(k)];
}

}  // namespace meshmorph::detail
