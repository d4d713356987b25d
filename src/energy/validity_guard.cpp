// SPDX-License-Identifier: MIT
#include "meshmorph/energy/validity_guard.h"

#include <algorithm>
#include <limits>

#include <Eigen/LU>

#include "meshmorph/energy/element_energy.h"
#include "meshmorph/error.h"
#include "meshmorph/fem/quadrature.h"
#include "meshmorph/fem/shape_table.h"
#include "meshmorph/fem/validity.h"

namespace meshmorph {

template <int d>
ValidityGuard<d>::ValidityGuard(const Mesh& input, const DofMap& dofs) : mesh_(&input), dofs_(&dofs) {
  MESHMORPH_CHECK(input.dim == d, "ValidityGuard: the mesh's dimension differs from the guard's");
  std::size_t first = 0;
  for (const CellBlock& block : input.cells) {
    block_first_.push_back(first);
    first += block.n_cells();
  }
  guarded_.assign(first, false);
}

template <int d>
Eigen::Matrix<double, d, Eigen::Dynamic> ValidityGuard<d>::coordinates(const Cell& c, const Eigen::MatrixXd& x) const {
  const CellBlock& block = mesh_->cells[c.block];
  const int n = block.n_nodes_per_cell();
  Eigen::Matrix<double, d, Eigen::Dynamic> X(d, n);
  const std::int32_t* nodes = block.cell(c.local);
  for (int a = 0; a < n; ++a) X.col(a) = x.col(nodes[a]);
  return X;
}

template <int d>
std::size_t ValidityGuard<d>::add(std::span<const std::size_t> cells) {
  std::size_t added = 0;
  for (std::size_t index : cells) {
    MESHMORPH_CHECK(index < guarded_.size(), "ValidityGuard: no such cell");
    if (guarded_[index]) continue;
    Cell c;
    c.index = index;
    c.block = static_cast<std::size_t>(std::upper_bound(block_first_.begin(), block_first_.end(), index) -
                                       block_first_.begin()) - 1;
    c.local = index - block_first_[c.block];
    const CellBlock& block = mesh_->cells[c.block];
    const ShapeTable& samples = validity_samples(block.type, block.order);
    const double reference = shape_table(block.type, block.order, metric_quadrature_degree(block.type, block.order))
                                 .weights.sum();
    const Eigen::Matrix<double, d, Eigen::Dynamic> W0 = coordinates(c, mesh_->x);
    c.samples.resize(static_cast<std::size_t>(samples.n_points()));
    for (int s = 0; s < samples.n_points(); ++s) {
      const MatT<d> W = W0 * samples.grad(s);
      const double det = W.determinant();
      // A sample where the input itself is singular has no target: left out (weight 0, W⁻¹ = I).
      c.samples[static_cast<std::size_t>(s)] =
          det > 0.0 ? QuadratureTarget<d>{W.inverse(), reference * det / samples.n_points()}
                    : QuadratureTarget<d>{MatT<d>::Identity(), 0.0};
    }
    cells_.push_back(std::move(c));
    guarded_[index] = true;
    ++added;
  }
  return added;
}

template <int d>
double ValidityGuard<d>::value(const Metric<d>& metric, const Eigen::MatrixXd& x,
                               std::span<const double> weights) const {
  double total = 0.0;
  for (const Cell& c : cells_) {
    const CellBlock& block = mesh_->cells[c.block];
    const ElementEnergy e = element_energy<d>(metric, validity_samples(block.type, block.order), c.samples,
                                              coordinates(c, x), Want::Value);
    if (!(e.value < std::numeric_limits<double>::infinity())) return std::numeric_limits<double>::infinity();
    total += (weights.empty() ? 1.0 : weights[c.index]) * e.value;
  }
  return total;
}

template <int d>
void ValidityGuard<d>::add_to(const Metric<d>& metric, const Eigen::MatrixXd& x, std::span<const double> weights,
                              Want want, HessianMode mode, Assembly& out) const {
  const int* outer = out.hessian.outerIndexPtr();
  const int* inner = out.hessian.innerIndexPtr();
  double* values = out.hessian.valuePtr();
  std::vector<std::int32_t> dof;
  for (const Cell& c : cells_) {
    const CellBlock& block = mesh_->cells[c.block];
    const ElementEnergy e = element_energy<d>(metric, validity_samples(block.type, block.order), c.samples,
                                              coordinates(c, x), want, mode);
    if (!(e.value < std::numeric_limits<double>::infinity())) {
      out.value = std::numeric_limits<double>::infinity();
      return;
    }
    const double w = weights.empty() ? 1.0 : weights[c.index];
    out.value += w * e.value;
    if (want == Want::Value) continue;
    const int n = block.n_nodes_per_cell();
    dof.resize(static_cast<std::size_t>(d * n));
    for (int a = 0; a < n; ++a)
      for (int k = 0; k < d; ++k)
        dof[static_cast<std::size_t>(d * a + k)] =
            dofs_->reduced(static_cast<std::size_t>(d) * static_cast<std::size_t>(block.cell(c.local)[a]) + k);
    for (int i = 0; i < d * n; ++i)
      if (dof[static_cast<std::size_t>(i)] >= 0) out.gradient[dof[static_cast<std::size_t>(i)]] += w * e.gradient[i];
    if (want != Want::Hessian) continue;
    for (int j = 0; j < d * n; ++j) {
      const std::int32_t col = dof[static_cast<std::size_t>(j)];
      if (col < 0) continue;
      for (int i = 0; i < d * n; ++i) {
        const std::int32_t row = dof[static_cast<std::size_t>(i)];
        if (row < 0) continue;
        const int* at = std::lower_bound(inner + outer[col], inner + outer[col + 1], row);
        MESHMORPH_CHECK(at != inner + outer[col + 1] && *at == row,
                        "ValidityGuard: the Hessian's pattern lacks a pair of DOFs of one cell");
        values[at - inner] += w * e.hessian(i, j);
      }
    }
  }
}

template class ValidityGuard<2>;
template class ValidityGuard<3>;

}  // namespace meshmorph
