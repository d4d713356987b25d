// SPDX-License-Identifier: MIT
#include "meshmorph/energy/boundary_penalty.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <Eigen/Geometry>
#include <Eigen/LU>

#include "meshmorph/error.h"
#include "meshmorph/fem/jacobian.h"
#include "meshmorph/fem/quadrature.h"
#include "meshmorph/fem/shape_table.h"
#include "meshmorph/fem/trace.h"

namespace meshmorph {
namespace {

// Measure of the straight facet through the given corners (a segment, triangle or quadrilateral
// split into two triangles).
double straight_facet_measure(const Eigen::MatrixXd& corners) {
  const int d = static_cast<int>(corners.rows());
  const auto n = corners.cols();
  if (d == 2) return (corners.col(1) - corners.col(0)).norm();
  auto tri = [&](int a, int b, int c) {
    const Eigen::Vector3d u = corners.col(b) - corners.col(a), v = corners.col(c) - corners.col(a);
    return 0.5 * u.cross(v).norm();
  };
  return n == 3 ? tri(0, 1, 2) : tri(0, 1, 2) + tri(0, 2, 3);
}

// In-radius d·V/S of one cell: V integrated with the cell's own map, S from its straight facets.
double in_radius(const Mesh& mesh, const CellBlock& block, std::size_t cell) {
  const Eigen::MatrixXd X = cell_coordinates(mesh, block, cell);
  const ShapeTable& table = shape_table(block.type, block.order, metric_quadrature_degree(block.type, block.order));
  double volume = 0.0;
  for (int q = 0; q < table.n_points(); ++q) volume += table.weights[q] * std::abs(jacobian(X, table, q).determinant());
  double surface = 0.0;
  for (const std::vector<int>& facet : corner_facets(block.type)) {
    Eigen::MatrixXd corners(mesh.dim, static_cast<Eigen::Index>(facet.size()));
    for (std::size_t i = 0; i < facet.size(); ++i) corners.col(static_cast<Eigen::Index>(i)) = X.col(facet[i]);
    surface += straight_facet_measure(corners);
  }
  return mesh.dim * volume / surface;
}

}  // namespace

BoundaryMass boundary_mass(const Mesh& mesh, const Topology& topology, const Eigen::MatrixXd& x) {
  BoundaryMass out;
  out.nodes = boundary_nodes(mesh, topology);
  std::vector<std::int32_t> local(mesh.n_nodes(), -1);
  for (std::size_t i = 0; i < out.nodes.size(); ++i) local[out.nodes[i]] = static_cast<std::int32_t>(i);

  Mesh at_x = mesh;  // cell_coordinates reads mesh.x
  at_x.x = x;
  std::vector<Eigen::Triplet<double>> triplets;
  for (std::int32_t f : topology.boundary_facets) {
    const CellFacet cf = topology.facets[f][0];
    const auto [bi, c] = topology.locate(cf.cell);
    const CellBlock& block = mesh.cells[bi];
    const double h = in_radius(at_x, block, c);
    MESHMORPH_CHECK(h > 0.0 && std::isfinite(h), "boundary_mass: a boundary cell has no volume");
    const std::vector<std::int32_t> fnodes = facet_nodes(block, c, cf.local);
    const ElementType ftype = facet_type(block.type, cf.local);
    // Degree 2p + 1: the mass N_a N_b of a straight facet exactly, curved ones accurately.
    const ShapeTable& table = shape_table(ftype, block.order, 2 * block.order + 1);
    const auto n = static_cast<Eigen::Index>(fnodes.size());
    Eigen::MatrixXd X(mesh.dim, n);
    for (Eigen::Index a = 0; a < n; ++a) X.col(a) = x.col(fnodes[a]);
    Eigen::MatrixXd Mf = Eigen::MatrixXd::Zero(n, n);
    for (int q = 0; q < table.n_points(); ++q) {
      const Eigen::MatrixXd J = X * table.grad(q);  // d × (d − 1)
      const double dgamma = table.weights[q] * std::sqrt((J.transpose() * J).determinant());
      Mf.noalias() += dgamma * table.N.col(q) * table.N.col(q).transpose();
    }
    for (Eigen::Index a = 0; a < n; ++a)
      for (Eigen::Index b = 0; b < n; ++b)
        triplets.emplace_back(local[fnodes[a]], local[fnodes[b]], Mf(a, b) / h);
  }
  const auto m = static_cast<Eigen::Index>(out.nodes.size());
  out.M.resize(m, m);
  out.M.setFromTriplets(triplets.begin(), triplets.end());
  return out;
}

template <int d>
BoundaryPenalty<d>::BoundaryPenalty(const BoundaryMass& mass, std::vector<std::int32_t> nodes) : nodes_(std::move(nodes)) {
  const auto m = static_cast<Eigen::Index>(nodes_.size());
  std::vector<Eigen::Index> pos(nodes_.size());
  for (std::size_t i = 0; i < nodes_.size(); ++i) {
    const auto it = std::lower_bound(mass.nodes.begin(), mass.nodes.end(), nodes_[i]);
    MESHMORPH_CHECK(it != mass.nodes.end() && *it == nodes_[i],
                    "BoundaryPenalty: node " + std::to_string(nodes_[i]) + " is not on the boundary");
    pos[i] = it - mass.nodes.begin();
  }
  // M restricted to the constrained nodes: P M Pᵀ with a selection matrix.
  std::vector<Eigen::Index> slot(static_cast<std::size_t>(mass.M.rows()), -1);
  for (std::size_t i = 0; i < pos.size(); ++i) slot[static_cast<std::size_t>(pos[i])] = static_cast<Eigen::Index>(i);
  std::vector<Eigen::Triplet<double>> t;
  for (Eigen::Index col = 0; col < mass.M.outerSize(); ++col)
    for (Eigen::SparseMatrix<double>::InnerIterator it(mass.M, col); it; ++it) {
      const Eigen::Index a = slot[static_cast<std::size_t>(it.row())], b = slot[static_cast<std::size_t>(col)];
      if (a >= 0 && b >= 0) t.emplace_back(a, b, it.value());
    }
  M_.resize(m, m);
  M_.setFromTriplets(t.begin(), t.end());
  total_ = M_.sum();
  g_ = Eigen::MatrixXd::Zero(d, m);
  lambda_ = Eigen::MatrixXd::Zero(d, m);
}

template <int d>
Eigen::MatrixXd BoundaryPenalty<d>::residual(const Eigen::MatrixXd& x) const {
  Eigen::MatrixXd r(d, static_cast<Eigen::Index>(nodes_.size()));
  for (std::size_t a = 0; a < nodes_.size(); ++a) r.col(static_cast<Eigen::Index>(a)) = x.col(nodes_[a]) - g_.col(static_cast<Eigen::Index>(a));
  return r;
}

template <int d>
double BoundaryPenalty<d>::value(const Eigen::MatrixXd& x) const {
  const Eigen::MatrixXd r = residual(x);
  const Eigen::MatrixXd rM = r * M_;  // M symmetric: (M rᵀ)ᵀ
  return -(lambda_.cwiseProduct(rM)).sum() + 0.5 * mu * (r.cwiseProduct(rM)).sum();
}

template <int d>
double BoundaryPenalty<d>::constraint_norm(const Eigen::MatrixXd& x) const {
  if (nodes_.empty() || total_ <= 0.0) return 0.0;
  const Eigen::MatrixXd r = residual(x);
  return std::sqrt(std::max(0.0, (r.cwiseProduct(r * M_)).sum()) / total_);
}

template <int d>
double BoundaryPenalty<d>::max_error(const Eigen::MatrixXd& x) const {
  if (nodes_.empty()) return 0.0;
  return residual(x).colwise().norm().maxCoeff();
}

template <int d>
double BoundaryPenalty<d>::mean_diagonal() const {
  return nodes_.empty() ? 0.0 : M_.diagonal().mean();
}

template <int d>
void BoundaryPenalty<d>::bind(const EnergyAssembler<d>& assembler, const Eigen::SparseMatrix<double>& H) {
  const DofMap& dofs = assembler.dofs();
  hessian_offsets_.clear();
  hessian_offsets_.reserve(static_cast<std::size_t>(M_.nonZeros()) * d * d);
  for (Eigen::Index col = 0; col < M_.outerSize(); ++col)
    for (Eigen::SparseMatrix<double>::InnerIterator it(M_, col); it; ++it)
      for (int l = 0; l < d; ++l)
        for (int k = 0; k < d; ++k) {
          const std::int32_t i = dofs.reduced(static_cast<std::size_t>(d) * nodes_[it.row()] + k);
          const std::int32_t j = dofs.reduced(static_cast<std::size_t>(d) * nodes_[col] + l);
          std::int64_t offset = -1;
          if (i >= 0 && j >= 0) {
            const int* begin = H.innerIndexPtr() + H.outerIndexPtr()[j];
            const int* end = H.innerIndexPtr() + H.outerIndexPtr()[j + 1];
            const int* found = std::lower_bound(begin, end, i);
            MESHMORPH_ASSERT(found != end && *found == i);
            offset = found - H.innerIndexPtr();
          }
          hessian_offsets_.push_back(offset);
        }
  bound_ = &assembler;
}

template <int d>
void BoundaryPenalty<d>::add_to(const EnergyAssembler<d>& assembler, const Eigen::MatrixXd& x, Want want, Assembly& out) {
  const Eigen::MatrixXd r = residual(x);
  const Eigen::MatrixXd rM = r * M_;
  out.value += -(lambda_.cwiseProduct(rM)).sum() + 0.5 * mu * (r.cwiseProduct(rM)).sum();
  if (want == Want::Value) return;
  const DofMap& dofs = assembler.dofs();
  const Eigen::MatrixXd grad = mu * rM - lambda_ * M_;  // ∂E_b/∂x_a = Σ_b M_ab (μ r_b − λ_b)
  for (std::size_t a = 0; a < nodes_.size(); ++a)
    for (int k = 0; k < d; ++k) {
      const std::int32_t i = dofs.reduced(static_cast<std::size_t>(d) * nodes_[a] + k);
      if (i >= 0) out.gradient[i] += grad(k, static_cast<Eigen::Index>(a));
    }
  if (want != Want::Hessian) return;
  if (bound_ != &assembler) bind(assembler, out.hessian);
  double* values = out.hessian.valuePtr();
  std::size_t e = 0;
  for (Eigen::Index col = 0; col < M_.outerSize(); ++col)
    for (Eigen::SparseMatrix<double>::InnerIterator it(M_, col); it; ++it) {
      // μ M_ab I: only the diagonal of each d × d block.
      const double v = mu * it.value();
      for (int l = 0; l < d; ++l)
        for (int k = 0; k < d; ++k, ++e)
          if (k == l && hessian_offsets_[e] >= 0) values[hessian_offsets_[e]] += v;
    }
}

template class BoundaryPenalty<2>;
template class BoundaryPenalty<3>;

}  // namespace meshmorph
