// SPDX-License-Identifier: MIT
#include "meshmorph/energy/coarse_space.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <Eigen/LU>

#include "meshmorph/error.h"
#include "meshmorph/fem/reference_element.h"

namespace meshmorph {
namespace {

// Hat values (corners) and reference gradients (corners × dim) at ξ of the linear simplex or
// multilinear tensor cell whose corners are the first nodes of `ref`.
struct Hats {
  Eigen::VectorXd value;
  Eigen::MatrixXd gradient;
};

Hats hats_at(const ReferenceElement& ref, int corners, const Eigen::VectorXd& xi) {
  const int dim = ref.dim;
  Hats h{Eigen::VectorXd(corners), Eigen::MatrixXd(corners, dim)};
  if (is_simplex(ref.type)) {
    // Barycentric coordinates: [1; ξ] = C λ with C's columns [1; corner v].
    Eigen::MatrixXd C(dim + 1, corners);
    C.row(0).setOnes();
    C.bottomRows(dim) = ref.nodes.leftCols(corners);
    const Eigen::MatrixXd Cinv = C.inverse();
    Eigen::VectorXd one_xi(dim + 1);
    one_xi << 1.0, xi;
    h.value = Cinv * one_xi;
    h.gradient = Cinv.rightCols(dim);
    return h;
  }
  // Corners at ±1: hat_v = Π_k (1 + c_k ξ_k) / 2.
  for (int v = 0; v < corners; ++v)
    for (int j = -1; j < dim; ++j) {
      double p = 1.0;
      for (int k = 0; k < dim; ++k) {
        const double c = ref.nodes(k, v);
        p *= k == j ? c / 2.0 : (1.0 + c * xi[k]) / 2.0;
      }
      if (j < 0)
        h.value[v] = p;
      else
        h.gradient(v, j) = p;
    }
  return h;
}

}  // namespace

template <int d>
CoarseSpace<d>::CoarseSpace(const Mesh& mesh, const DofMap& dofs, const TargetField<d>& targets) {
  MESHMORPH_CHECK(mesh.dim == d && dofs.dim() == d && dofs.n_nodes() == mesh.n_nodes(), "CoarseSpace: the DofMap does not fit the mesh");
  MESHMORPH_CHECK(targets.blocks.size() == mesh.cells.size(), "CoarseSpace: the targets do not fit the mesh");
  const std::int32_t* red = dofs.reduced_index().data();
  constexpr double k_zero = 1e-14;  // a hat value below this is zero (at the other corners' nodes)
  std::vector<std::int32_t> vertex(mesh.n_nodes(), -1);
  std::int32_t n_vertices = 0;
  blocks_.resize(mesh.cells.size());
  for (std::size_t b = 0; b < mesh.cells.size(); ++b) {
    const CellBlock& block = mesh.cells[b];
    MESHMORPH_CHECK(topological_dim(block.type) == d, "CoarseSpace: cell block " + std::to_string(b) + " is not of dimension d");
    const ReferenceElement& ref = reference_element(block.type, block.order);
    Block& cb = blocks_[b];
    cb.corners = n_corners_of(block.type);
    const int n = block.n_nodes_per_cell();
    cb.values.resize(n, cb.corners);
    for (int a = 0; a < n; ++a) cb.values.row(a) = hats_at(ref, cb.corners, ref.nodes.col(a)).value.transpose();
    const ShapeTable& table = *targets.blocks[b].table;
    for (int q = 0; q < table.n_points(); ++q) cb.gradients.push_back(hats_at(ref, cb.corners, table.points.col(q)).gradient);
    for (std::size_t c = 0; c < block.n_cells(); ++c)
      for (int v = 0; v < cb.corners; ++v)
        if (std::int32_t& id = vertex[static_cast<std::size_t>(block.cell(c)[v])]; id < 0) id = n_vertices++;
  }
  // A coarse DOF is dropped where its hat is nonzero at a fixed DOF of its component.
  std::vector<std::uint8_t> kept(static_cast<std::size_t>(d) * n_vertices, 1);
  for (std::size_t b = 0; b < mesh.cells.size(); ++b) {
    const CellBlock& block = mesh.cells[b];
    const Block& cb = blocks_[b];
    for (std::size_t c = 0; c < block.n_cells(); ++c)
      for (int a = 0; a < block.n_nodes_per_cell(); ++a)
        for (int v = 0; v < cb.corners; ++v)
          for (int k = 0; k < d; ++k)
            if (std::abs(cb.values(a, v)) > k_zero && red[d * block.cell(c)[a] + k] < 0)
              kept[static_cast<std::size_t>(d * vertex[static_cast<std::size_t>(block.cell(c)[v])] + k)] = 0;
  }
  std::vector<std::int32_t> index(kept.size(), -1);
  std::int32_t n_coarse = 0;
  for (std::size_t i = 0; i < kept.size(); ++i)
    if (kept[i]) index[i] = n_coarse++;
  cell_dofs_.resize(mesh.cells.size());
  std::vector<Eigen::Triplet<double>> entries;
  std::vector<std::uint8_t> done(mesh.n_nodes(), 0);
  for (std::size_t b = 0; b < mesh.cells.size(); ++b) {
    const CellBlock& block = mesh.cells[b];
    const Block& cb = blocks_[b];
    std::vector<std::int32_t>& ids = cell_dofs_[b];
    ids.resize(block.n_cells() * static_cast<std::size_t>(cb.corners) * d);
    for (std::size_t c = 0; c < block.n_cells(); ++c) {
      const std::int32_t* nodes = block.cell(c);
      for (int v = 0; v < cb.corners; ++v)
        for (int k = 0; k < d; ++k)
          ids[(c * static_cast<std::size_t>(cb.corners) + static_cast<std::size_t>(v)) * d + static_cast<std::size_t>(k)] =
              index[static_cast<std::size_t>(d * vertex[static_cast<std::size_t>(nodes[v])] + k)];
      // R's rows of the cell's nodes, once per node (the hats agree between the cells at it).
      for (int a = 0; a < block.n_nodes_per_cell(); ++a) {
        if (done[static_cast<std::size_t>(nodes[a])]) continue;
        done[static_cast<std::size_t>(nodes[a])] = 1;
        for (int v = 0; v < cb.corners; ++v)
          for (int k = 0; k < d; ++k) {
            const std::int32_t row = red[d * nodes[a] + k];
            const std::int32_t col = index[static_cast<std::size_t>(d * vertex[static_cast<std::size_t>(nodes[v])] + k)];
            if (row >= 0 && col >= 0 && std::abs(cb.values(a, v)) > k_zero) entries.emplace_back(row, col, cb.values(a, v));
          }
      }
    }
  }
  R_.resize(static_cast<Eigen::Index>(dofs.n_free()), n_coarse);
  R_.setFromTriplets(entries.begin(), entries.end());
  // The pattern: every pair of kept coarse DOFs of a cell.
  entries.clear();
  for (std::size_t b = 0; b < mesh.cells.size(); ++b) {
    const int m = d * blocks_[b].corners;
    for (std::size_t c = 0; c < mesh.cells[b].n_cells(); ++c)
      for (int j = 0; j < m; ++j)
        for (int i = 0; i < m; ++i) {
          const std::int32_t row = dof(b, c, i / d, i % d), col = dof(b, c, j / d, j % d);
          if (row >= 0 && col >= 0) entries.emplace_back(row, col, 0.0);
        }
  }
  pattern_.resize(n_coarse, n_coarse);
  pattern_.setFromTriplets(entries.begin(), entries.end());
  pattern_.makeCompressed();
  scatter_.resize(mesh.cells.size());
  for (std::size_t b = 0; b < mesh.cells.size(); ++b) {
    const int m = d * blocks_[b].corners;
    std::vector<std::int32_t>& off = scatter_[b];
    off.assign(mesh.cells[b].n_cells() * static_cast<std::size_t>(m * m), -1);
    for (std::size_t c = 0; c < mesh.cells[b].n_cells(); ++c)
      for (int j = 0; j < m; ++j) {
        const std::int32_t col = dof(b, c, j / d, j % d);
        if (col < 0) continue;
        const int* first = pattern_.innerIndexPtr() + pattern_.outerIndexPtr()[col];
        const int* last = pattern_.innerIndexPtr() + pattern_.outerIndexPtr()[col + 1];
        for (int i = 0; i < m; ++i)
          if (const std::int32_t row = dof(b, c, i / d, i % d); row >= 0)
            off[c * static_cast<std::size_t>(m * m) + static_cast<std::size_t>(i + m * j)] =
                static_cast<std::int32_t>(std::lower_bound(first, last, row) - pattern_.innerIndexPtr());
      }
  }
}

template class CoarseSpace<2>;
template class CoarseSpace<3>;

}  // namespace meshmorph
