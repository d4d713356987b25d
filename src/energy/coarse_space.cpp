// SPDX-License-Identifier: MIT
#include "meshmorph/energy/coarse_space.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <Eigen/LU>

#include "meshmorph/error.h"
#include "meshmorph/fem/lagrange_basis.h"
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
  if (ref.type == ElementType::Prism || ref.type == ElementType::Pyramid) {  // their own P1 bases
    const LagrangeBasis& p1 = lagrange_basis(ref.type, 1);
    return {p1.values(xi), p1.gradients(xi)};
  }
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

// Each block's corner hats at its nodes (nodes × corners).
std::vector<Eigen::MatrixXd> hat_values(const Mesh& mesh) {
  std::vector<Eigen::MatrixXd> values(mesh.cells.size());
  for (std::size_t b = 0; b < mesh.cells.size(); ++b) {
    const CellBlock& block = mesh.cells[b];
    const ReferenceElement& ref = reference_element(block.type, block.order);
    const int corners = n_corners_of(block.type), n = block.n_nodes_per_cell();
    values[b].resize(n, corners);
    for (int a = 0; a < n; ++a) values[b].row(a) = hats_at(ref, corners, ref.nodes.col(a)).value.transpose();
  }
  return values;
}

// The hats at the free DOFs: the vertex number of each mesh node (−1 for non-corners), the
// coarse DOF of each (vertex, component) (−1 where dropped) and R. A coarse DOF is dropped
// where its hat is nonzero at a fixed DOF of its component; with `whole_vertices`, all of
// its vertex's components are dropped with it.
template <int d>
struct HatSpace {
  std::vector<std::int32_t> vertex, index;
  Eigen::SparseMatrix<double> R;

  HatSpace(const Mesh& mesh, const DofMap& dofs, const std::vector<Eigen::MatrixXd>& values, bool whole_vertices) {
    MESHMORPH_CHECK(mesh.dim == d && dofs.dim() == d && dofs.n_nodes() == mesh.n_nodes(), "CoarseSpace: the DofMap does not fit the mesh");
    const std::int32_t* red = dofs.reduced_index().data();
    constexpr double k_zero = 1e-14;  // a hat value below this is zero (at the other corners' nodes)
    vertex.assign(mesh.n_nodes(), -1);
    std::int32_t n_vertices = 0;
    for (std::size_t b = 0; b < mesh.cells.size(); ++b) {
      const CellBlock& block = mesh.cells[b];
      MESHMORPH_CHECK(topological_dim(block.type) == d, "CoarseSpace: cell block " + std::to_string(b) + " is not of dimension d");
      for (std::size_t c = 0; c < block.n_cells(); ++c)
        for (int v = 0; v < values[b].cols(); ++v)
          if (std::int32_t& id = vertex[static_cast<std::size_t>(block.cell(c)[v])]; id < 0) id = n_vertices++;
    }
    std::vector<std::uint8_t> kept(static_cast<std::size_t>(d) * n_vertices, 1);
    for (std::size_t b = 0; b < mesh.cells.size(); ++b) {
      const CellBlock& block = mesh.cells[b];
      for (std::size_t c = 0; c < block.n_cells(); ++c)
        for (int a = 0; a < block.n_nodes_per_cell(); ++a)
          for (int v = 0; v < values[b].cols(); ++v)
            for (int k = 0; k < d; ++k)
              if (std::abs(values[b](a, v)) > k_zero && red[d * block.cell(c)[a] + k] < 0) {
                const auto first = static_cast<std::size_t>(d * vertex[static_cast<std::size_t>(block.cell(c)[v])]);
                if (whole_vertices)
                  std::fill_n(kept.begin() + static_cast<std::ptrdiff_t>(first), d, 0);
                else
                  kept[first + static_cast<std::size_t>(k)] = 0;
              }
    }
    index.assign(kept.size(), -1);
    std::int32_t n_coarse = 0;
    for (std::size_t i = 0; i < kept.size(); ++i)
      if (kept[i]) index[i] = n_coarse++;
    // R's rows of each node, once (the hats agree between the cells at it).
    std::vector<Eigen::Triplet<double>> entries;
    std::vector<std::uint8_t> done(mesh.n_nodes(), 0);
    for (std::size_t b = 0; b < mesh.cells.size(); ++b) {
      const CellBlock& block = mesh.cells[b];
      for (std::size_t c = 0; c < block.n_cells(); ++c) {
        const std::int32_t* nodes = block.cell(c);
        for (int a = 0; a < block.n_nodes_per_cell(); ++a) {
          if (done[static_cast<std::size_t>(nodes[a])]) continue;
          done[static_cast<std::size_t>(nodes[a])] = 1;
          for (int v = 0; v < values[b].cols(); ++v)
            for (int k = 0; k < d; ++k) {
              const std::int32_t row = red[d * nodes[a] + k];
              const std::int32_t col = index[static_cast<std::size_t>(d * vertex[static_cast<std::size_t>(nodes[v])] + k)];
              if (row >= 0 && col >= 0 && std::abs(values[b](a, v)) > k_zero) entries.emplace_back(row, col, values[b](a, v));
            }
        }
      }
    }
    R.resize(static_cast<Eigen::Index>(dofs.n_free()), n_coarse);
    R.setFromTriplets(entries.begin(), entries.end());
  }
};

}  // namespace

template <int d>
Eigen::SparseMatrix<double> vertex_hats(const Mesh& mesh, const DofMap& dofs) {
  return HatSpace<d>(mesh, dofs, hat_values(mesh), true).R;
}

template <int d>
CoarseSpace<d>::CoarseSpace(const Mesh& mesh, const DofMap& dofs, const TargetField<d>& targets) {
  MESHMORPH_CHECK(targets.blocks.size() == mesh.cells.size(), "CoarseSpace: the targets do not fit the mesh");
  const std::vector<Eigen::MatrixXd> values = hat_values(mesh);
  HatSpace<d> hats(mesh, dofs, values, false);
  R_ = std::move(hats.R);
  blocks_.resize(mesh.cells.size());
  cell_dofs_.resize(mesh.cells.size());
  for (std::size_t b = 0; b < mesh.cells.size(); ++b) {
    const CellBlock& block = mesh.cells[b];
    const ReferenceElement& ref = reference_element(block.type, block.order);
    Block& cb = blocks_[b];
    cb.corners = n_corners_of(block.type);
    cb.values = values[b];
    const ShapeTable& table = *targets.blocks[b].table;
    for (int q = 0; q < table.n_points(); ++q) cb.gradients.push_back(hats_at(ref, cb.corners, table.points.col(q)).gradient);
    std::vector<std::int32_t>& ids = cell_dofs_[b];
    ids.resize(block.n_cells() * static_cast<std::size_t>(cb.corners) * d);
    for (std::size_t c = 0; c < block.n_cells(); ++c)
      for (int v = 0; v < cb.corners; ++v)
        for (int k = 0; k < d; ++k)
          ids[(c * static_cast<std::size_t>(cb.corners) + static_cast<std::size_t>(v)) * d + static_cast<std::size_t>(k)] =
              hats.index[static_cast<std::size_t>(d * hats.vertex[static_cast<std::size_t>(block.cell(c)[v])] + k)];
  }
  const auto n_coarse = static_cast<std::int32_t>(R_.cols());
  std::vector<Eigen::Triplet<double>> entries;
  // The pattern: every pair of kept coarse DOFs of a cell.
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
template Eigen::SparseMatrix<double> vertex_hats<2>(const Mesh&, const DofMap&);
template Eigen::SparseMatrix<double> vertex_hats<3>(const Mesh&, const DofMap&);

}  // namespace meshmorph
