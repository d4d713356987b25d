// SPDX-License-Identifier: MIT
#include "methods/detail/stiffness.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/LU>

#include "energy/detail/pattern.h"
#include "meshmorph/energy/dof_map.h"
#include "meshmorph/error.h"
#include "meshmorph/fem/shape_table.h"
#include "meshmorph/threads.h"

namespace meshmorph::detail {
namespace {

// Below this many cells a block is assembled by one thread: the barriers between colours
// would cost more than the work (and spin long on a loaded machine).
constexpr std::int64_t k_min_parallel_cells = 512;

// Degree that makes the discrete equations of an affine displacement exact on any (also
// curved) isoparametric cell: the integrand of ∫ C:∇v is cof(A)ᵀ∇_ξN, a polynomial of total
// degree d(p−1) on simplices and of degree d·p per variable on tensor cells.
int stiffness_degree(ElementType type, int order, int d) {
  return is_simplex(type) ? std::max(1, d * (order - 1)) : d * order;
}

template <int d>
using MatD = Eigen::Matrix<double, d, d>;

// Physical gradients G (n × d) and volume measure det A at point q of cell X (d × n).
template <int d>
double physical_gradients(const Eigen::MatrixXd& X, const ShapeTable& table, int q, Eigen::MatrixXd& G) {
  const MatD<d> A = X * table.grad(q);
  const double det = A.determinant();
  if (!(det > 0.0)) return det;
  G.noalias() = table.grad(q) * A.inverse();
  return det;
}

template <int d>
Eigen::MatrixXd gather(const Mesh& mesh, const std::int32_t* nodes, int n) {
  Eigen::MatrixXd X(d, n);
  for (int a = 0; a < n; ++a) X.col(a) = mesh.x.col(nodes[a]);
  return X;
}

// Mean of J = det A · |reference cell| over every quadrature point; throws on det A ≤ 0.
template <int d>
double mean_jacobian(const Mesh& mesh, const Topology& topology, int threads, std::string_view method) {
  std::vector<double> cell_sum(mesh.n_cells(), 0.0);
  std::int64_t points = 0;
  std::int64_t first_bad = std::numeric_limits<std::int64_t>::max();
  for (std::size_t bi = 0; bi < mesh.cells.size(); ++bi) {
    const CellBlock& block = mesh.cells[bi];
    const ShapeTable& table = shape_table(block.type, block.order, stiffness_degree(block.type, block.order, d));
    const double ref = table.weights.sum();
    const auto base = static_cast<std::int64_t>(topology.block_offset[bi]);
    const auto n_cells = static_cast<std::int64_t>(block.n_cells());
    const int n = block.n_nodes_per_cell();
    points += n_cells * table.n_points();
#pragma omp parallel for schedule(static) num_threads(resolve_threads(threads)) reduction(min : first_bad) \
    if (n_cells >= k_min_parallel_cells)
    for (std::int64_t c = 0; c < n_cells; ++c) {
      const Eigen::MatrixXd X = gather<d>(mesh, block.cell(static_cast<std::size_t>(c)), n);
      double sum = 0.0;
      for (int q = 0; q < table.n_points(); ++q) {
        const double det = MatD<d>(X * table.grad(q)).determinant();
        if (!(det > 0.0)) first_bad = std::min(first_bad, base + c);
        sum += det * ref;
      }
      cell_sum[static_cast<std::size_t>(base + c)] = sum;
    }
  }
  if (first_bad != std::numeric_limits<std::int64_t>::max())
    throw InputError(std::string(method) + ": input cell " + std::to_string(first_bad) +
                     " (0-based, cell blocks concatenated) has det J <= 0 at a quadrature point; "
                     "the baselines need a valid input mesh");
  double total = 0.0;  // serial sum in cell order: the same J₀ for every thread count
  for (double s : cell_sum) total += s;
  return points > 0 ? total / static_cast<double>(points) : 1.0;
}

// Element matrix (d·n × d·n, interleaved a·d + i) at one quadrature point, upper triangle only.
template <int d>
void add_point(const StiffnessParams& p, const Eigen::MatrixXd& G, double w, Eigen::MatrixXd& Ke) {
  const auto n = static_cast<int>(G.rows());
  for (int b = 0; b < n; ++b)
    for (int a = 0; a <= b; ++a) {
      const double s = G.row(a).dot(G.row(b));
      if (p.kind == StiffnessKind::Laplace) {
        for (int k = 0; k < d; ++k) Ke(a * d + k, b * d + k) += w * s;
        continue;
      }
      for (int k = 0; k < d; ++k)
        for (int i = 0; i < d; ++i)
          Ke(a * d + i, b * d + k) +=
              w * (p.lambda * G(a, i) * G(b, k) + p.mu * G(a, k) * G(b, i) + (i == k ? p.mu * s : 0.0));
    }
}

template <int d>
Eigen::SparseMatrix<double> assemble(const Mesh& mesh, const Topology& topology, const StiffnessParams& p,
                                     std::string_view method) {
  const double j0 = mean_jacobian<d>(mesh, topology, p.threads, method);
  const bool stiffen = p.kind == StiffnessKind::Elastic && p.chi != 0.0;
  // All DOFs free: the energy layer's reduced pattern is then the full d×d-block pattern.
  const DofMap all = DofMap::all_free(d, mesh.n_nodes());
  const NodePattern pattern = build_node_pattern(topology, all);
  std::vector<int> outer;
  reduced_hessian_columns(all, pattern, outer);
  std::vector<int> inner(static_cast<std::size_t>(outer.back()));
  reduced_hessian_rows(topology, all, outer.data(), inner.data());
  const auto n_dofs = static_cast<Eigen::Index>(all.n_dofs());
  std::vector<double> values(inner.size(), 0.0);

  for (std::size_t bi = 0; bi < mesh.cells.size(); ++bi) {
    const CellBlock& block = mesh.cells[bi];
    const ShapeTable& table = shape_table(block.type, block.order, stiffness_degree(block.type, block.order, d));
    const double ref = table.weights.sum();
    const int n = block.n_nodes_per_cell();
    std::vector<std::int32_t> color_offset, order;
    color_cells(block, topology, topology.block_offset[bi], color_offset, order);
    const std::vector<std::int32_t> scatter = scatter_offsets(block, topology, pattern);
#pragma omp parallel num_threads(resolve_threads(p.threads)) \
    if (static_cast<std::int64_t>(block.n_cells()) >= k_min_parallel_cells)
    {
      Eigen::MatrixXd G(n, d), Ke(d * n, d * n);
      for (std::size_t color = 0; color + 1 < color_offset.size(); ++color) {
        // Cells of one colour share no node, so no two threads write the same entry and each
        // entry sums its cells in colour order: the same bits for any thread count.
#pragma omp for schedule(dynamic, 16)
        for (std::int32_t i = color_offset[color]; i < color_offset[color + 1]; ++i) {
          const auto c = static_cast<std::size_t>(order[static_cast<std::size_t>(i)]);
          const std::int32_t* nodes = block.cell(c);
          const Eigen::MatrixXd X = gather<d>(mesh, nodes, n);
          Ke.setZero();
          for (int q = 0; q < table.n_points(); ++q) {
            const double det = physical_gradients<d>(X, table, q, G);
            const double s = stiffen ? std::pow(j0 / (det * ref), p.chi) : 1.0;
            add_point<d>(p, G, table.weights[q] * det * s, Ke);
          }
          // Mirror the upper triangle: K is exactly symmetric, whatever the arithmetic above.
          for (int col = 0; col < d * n; ++col)
            for (int row = col + 1; row < d * n; ++row) Ke(row, col) = Ke(col, row);
          const std::int32_t* off = scatter.data() + c * static_cast<std::size_t>(n * n);
          for (int b = 0; b < n; ++b)
            for (int l = 0; l < d; ++l) {
              double* column = values.data() + outer[static_cast<std::size_t>(d * nodes[b] + l)];
              for (int a = 0; a < n; ++a)
                for (int k = 0; k < d; ++k) column[off[a + n * b] + k] += Ke(a * d + k, b * d + l);
            }
        }
      }
    }
  }
  Eigen::SparseMatrix<double> K(n_dofs, n_dofs);
  K.resizeNonZeros(static_cast<Eigen::Index>(inner.size()));
  std::copy(outer.begin(), outer.end(), K.outerIndexPtr());
  std::copy(inner.begin(), inner.end(), K.innerIndexPtr());
  std::copy(values.begin(), values.end(), K.valuePtr());
  return K;
}

}  // namespace

Eigen::SparseMatrix<double> assemble_stiffness(const Mesh& mesh, const Topology& topology,
                                               const StiffnessParams& params, std::string_view method) {
  MESHMORPH_CHECK(mesh.dim == 2 || mesh.dim == 3, std::string(method) + ": the mesh must be 2D or 3D");
  MESHMORPH_CHECK(topology.node_node_offset.size() == mesh.n_nodes() + 1,
                  std::string(method) + ": the topology does not fit the mesh");
  for (const CellBlock& block : mesh.cells)
    MESHMORPH_CHECK(topological_dim(block.type) == mesh.dim,
                    std::string(method) + ": cell blocks must have the mesh's dimension");
  return mesh.dim == 2 ? assemble<2>(mesh, topology, params, method) : assemble<3>(mesh, topology, params, method);
}

}  // namespace meshmorph::detail
