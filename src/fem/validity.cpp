// SPDX-License-Identifier: MIT
#include "meshmorph/fem/validity.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <mutex>

#include <Eigen/LU>

#include "meshmorph/error.h"
#include "meshmorph/fem/jacobian.h"
#include "meshmorph/fem/tensor_basis.h"
#include "meshmorph/timings.h"
#include "fem/detail/bezier_validity.h"

namespace meshmorph {

const ShapeTable& validity_samples(ElementType type, int order) {
  static std::mutex mutex;
  static std::map<std::pair<ElementType, int>, std::unique_ptr<ShapeTable>> cache;
  std::lock_guard lock(mutex);
  auto& slot = cache[{type, order}];
  if (!slot) {
    const auto& rule = quadrature_rule(type, metric_quadrature_degree(type, order));
    // A pyramid's apex has no gradient: its nodes but the apex (the linear pyramid's least
    // det A is at its base corners, detail::pyramid_min_det).
    const Eigen::MatrixXd& all = reference_element(type, order).nodes;
    Eigen::MatrixXd nodes = all;
    if (type == ElementType::Pyramid) {
      nodes.resize(3, all.cols() - 1);
      nodes << all.leftCols(4), all.rightCols(all.cols() - 5);
    }
    // det A is constant on linear simplices; elsewhere add the order-2p lattice (pyramids:
    // order ≥ 2, the collapsed box's lattice below the apex).
    const bool dense = type == ElementType::Pyramid ? order > 1 : (order > 1 || !is_simplex(type));
    Eigen::MatrixXd extra = dense ? detail::unit_lattice(type, 2 * order) : Eigen::MatrixXd(nodes.rows(), 0);
    if (is_tensor(type)) extra = (2.0 * extra.array() - 1.0).matrix();  // tensor cells live on [−1, 1]^d
    if (type == ElementType::Prism) extra.row(2) = (2.0 * extra.row(2).array() - 1.0).matrix();  // ζ ∈ [−1, 1]
    Eigen::MatrixXd pts(nodes.rows(), rule.points.cols() + nodes.cols() + extra.cols());
    pts << rule.points, nodes, extra;
    slot = std::make_unique<ShapeTable>(tabulate(type, order, pts));
  }
  return *slot;
}

namespace {

// Fixed-size d×d Jacobians: a closed-form determinant instead of a dynamic LU per sample
// (7% of a large optimize run was that LU).
template <int d>
double min_det_fixed(const ShapeTable& t, const Eigen::MatrixXd& X, const std::vector<std::uint8_t>* skip) {
  double m = std::numeric_limits<double>::infinity();
  for (int q = 0; q < t.n_points(); ++q) {
    if (skip && (*skip)[static_cast<std::size_t>(q)]) continue;
    const Eigen::Matrix<double, d, d> A = X.lazyProduct(t.grad(q));  // coefficient-wise: a GEMM per sample costs its packing
    const double det = A.determinant();
    if (!(det > -std::numeric_limits<double>::infinity())) return -std::numeric_limits<double>::infinity();  // NaN
    m = std::min(m, det);
  }
  return m;
}

// validity_samples of a quadrilateral or hexahedron as tensor grids of 1D point sets (the
// rule's, the lattice's, the nodes' where the lattice misses them): grid_gradients gives their
// Jacobians by sum factorization (a P3 hexahedron: 8× fewer operations than sample by sample).
// Empty where the samples are not such grids.
std::vector<TensorGrid> grid_samples(ElementType type, int order) {
  const TensorBasis& basis = tensor_basis(type, order);
  // The rule's grid as its shape table found it (ShapeTable::tensor).
  const std::shared_ptr<const TensorGrid>& rule = shape_table(type, order, metric_quadrature_degree(type, order)).tensor;
  if (basis.P == 0 || !rule) return {};
  std::vector<double> lattice;
  for (int i = 0; i <= 2 * order; ++i) lattice.push_back(2.0 * i / (2 * order) - 1.0);
  std::vector<std::vector<double>> sets = {lattice};
  const bool nodes_on_lattice = std::all_of(basis.nodes.begin(), basis.nodes.end(), [&](double v) {
    return std::any_of(lattice.begin(), lattice.end(), [&](double l) { return std::abs(l - v) < 1e-14; });
  });
  if (!nodes_on_lattice) sets.push_back(basis.nodes);
  std::vector<TensorGrid> grids = {*rule};
  for (const auto& x : sets) grids.push_back(tensor_grid(type, order, x));
  return grids;
}

const std::vector<TensorGrid>& tensor_samples(ElementType type, int order) {
  static std::mutex mutex;
  static std::map<std::pair<ElementType, int>, std::unique_ptr<std::vector<TensorGrid>>> cache;
  std::lock_guard lock(mutex);
  auto& slot = cache[{type, order}];
  if (!slot) slot = std::make_unique<std::vector<TensorGrid>>(grid_samples(type, order));
  return *slot;
}

// min det A over tensor grids (X: d × n, column-major).
template <int d>
double min_det_grids(const std::vector<TensorGrid>& grids, const Eigen::MatrixXd& X) {
  thread_local Eigen::VectorXd v;
  double lowest = std::numeric_limits<double>::infinity();
  for (const TensorGrid& g : grids) {
    detail::dets_on_grid<d>(g, X, v);
    lowest = std::min(lowest, v.minCoeff());
  }
  return lowest;
}

double min_det_samples(ElementType type, int order, const Eigen::MatrixXd& X, const std::vector<std::uint8_t>* skip) {
  if (!skip && X.rows() == topological_dim(type)) {
    const std::vector<TensorGrid>& grids = tensor_samples(type, order);
    if (!grids.empty() && X.rows() == 2) return min_det_grids<2>(grids, X);
    if (!grids.empty() && X.rows() == 3) return min_det_grids<3>(grids, X);
  }
  const auto& t = validity_samples(type, order);
  if (X.rows() == 2 && t.dim == 2) return min_det_fixed<2>(t, X, skip);
  if (X.rows() == 3 && t.dim == 3) return min_det_fixed<3>(t, X, skip);
  double m = std::numeric_limits<double>::infinity();
  for (int q = 0; q < t.n_points(); ++q) {
    if (skip && (*skip)[static_cast<std::size_t>(q)]) continue;
    const double det = jacobian(X, t, q).determinant();
    if (!(det > -std::numeric_limits<double>::infinity())) return -std::numeric_limits<double>::infinity();  // NaN
    m = std::min(m, det);
  }
  return m;
}

}  // namespace

double min_jacobian_det(ElementType type, int order, const Eigen::MatrixXd& X) {
  const double sampled = min_det_samples(type, order, X, nullptr);
  return sampled > 0.0 ? detail::bezier_min_det(type, order, X, sampled) : sampled;
}

double min_jacobian_det(ElementType type, int order, const Eigen::MatrixXd& X, const std::vector<std::uint8_t>& skip) {
  MESHMORPH_CHECK(skip.size() == static_cast<std::size_t>(validity_samples(type, order).n_points()),
                  "min_jacobian_det: one skip flag per validity sample");
  return min_det_samples(type, order, X, &skip);
}

std::vector<std::uint8_t> invalid_cells(const Mesh& mesh) {
  const PhaseTimer timer(Phase::Validity);
  std::vector<std::uint8_t> bad(mesh.n_cells(), 0);
  std::size_t offset = 0;
  for (const auto& b : mesh.cells) {
    const auto n = static_cast<std::int64_t>(b.n_cells());
#pragma omp parallel for schedule(static)
    for (std::int64_t c = 0; c < n; ++c) {
      const double det = min_jacobian_det(b.type, b.order, cell_coordinates(mesh, b, static_cast<std::size_t>(c)));
      bad[offset + static_cast<std::size_t>(c)] = !(det > 0) || !std::isfinite(det);
    }
    offset += b.n_cells();
  }
  return bad;
}

std::size_t count_invalid_cells(const Mesh& mesh) {
  const std::vector<std::uint8_t> bad = invalid_cells(mesh);
  return static_cast<std::size_t>(std::count(bad.begin(), bad.end(), std::uint8_t{1}));
}

}  // namespace meshmorph
