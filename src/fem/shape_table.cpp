// SPDX-License-Identifier: MIT
#include "meshmorph/fem/shape_table.h"

#include <cmath>
#include <map>
#include <memory>
#include <mutex>
#include <tuple>

#include "meshmorph/fem/jacobian.h"

namespace meshmorph {
namespace {

// The grid of `points` if they are the tensor grid of their first m coordinates (x fastest).
std::shared_ptr<const TensorGrid> grid_of(ElementType type, int order, const Eigen::MatrixXd& points) {
  const auto dim = static_cast<int>(points.rows());
  const auto Q = static_cast<int>(points.cols());
  const int m = static_cast<int>(std::lround(std::pow(Q, 1.0 / dim)));
  if (tensor_basis(type, order).P == 0 || static_cast<int>(std::lround(std::pow(m, dim))) != Q) return nullptr;
  for (int q = 0; q < Q; ++q)
    for (int k = 0, rest = q; k < dim; ++k, rest /= m)
      if (points(k, q) != points(0, rest % m)) return nullptr;
  std::vector<double> x(static_cast<std::size_t>(m));
  for (int q = 0; q < m; ++q) x[static_cast<std::size_t>(q)] = points(0, q);
  return std::make_shared<const TensorGrid>(tensor_grid(type, order, x));
}

}  // namespace

ShapeTable tabulate(ElementType type, int order, const Eigen::MatrixXd& points) {
  const auto& basis = lagrange_basis(type, order);
  ShapeTable t;
  t.type = type;
  t.order = order;
  t.dim = basis.dim();
  t.points = points;
  const auto np = static_cast<int>(points.cols());
  t.N.resize(basis.n(), np);
  t.dN.resize(basis.n(), t.dim * np);
  for (int q = 0; q < np; ++q) {
    t.N.col(q) = basis.values(points.col(q));
    t.dN.middleCols(q * t.dim, t.dim) = basis.gradients(points.col(q));
  }
  t.tensor = grid_of(type, order, points);
  return t;
}

const ShapeTable& shape_table(ElementType type, int order, int degree, QuadratureFamily family) {
  static std::mutex mutex;
  static std::map<std::tuple<ElementType, int, int, QuadratureFamily>, std::unique_ptr<ShapeTable>> cache;
  std::lock_guard lock(mutex);
  auto& slot = cache[{type, order, degree, family}];
  if (!slot) {
    const auto& rule = quadrature_rule(type, degree, family);
    slot = std::make_unique<ShapeTable>(tabulate(type, order, rule.points));
    slot->weights = rule.weights;
  }
  return *slot;
}

Eigen::MatrixXd cell_coordinates(const Mesh& mesh, const CellBlock& block, std::size_t cell) {
  const int n = block.n_nodes_per_cell();
  Eigen::MatrixXd X(mesh.dim, n);
  const auto* v = block.cell(cell);
  for (int a = 0; a < n; ++a) X.col(a) = mesh.x.col(v[a]);
  return X;
}

}  // namespace meshmorph
