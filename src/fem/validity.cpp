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

namespace meshmorph {
namespace {

// Points of the regular lattice of order m on the reference element.
Eigen::MatrixXd lattice(ElementType type, int m) {
  const int dim = topological_dim(type);
  const bool simplex = is_simplex(type);
  std::vector<Eigen::Vector3d> pts;
  for (int k = 0; k <= (dim > 2 ? m : 0); ++k)
    for (int j = 0; j <= m; ++j)
      for (int i = 0; i <= m; ++i) {
        if (simplex && i + j + k > m) continue;
        Eigen::Vector3d t(double(i) / m, double(j) / m, double(k) / m);
        pts.push_back(simplex ? t : Eigen::Vector3d(2 * t - Eigen::Vector3d::Ones()));
      }
  Eigen::MatrixXd X(dim, static_cast<Eigen::Index>(pts.size()));
  for (std::size_t p = 0; p < pts.size(); ++p) X.col(static_cast<Eigen::Index>(p)) = pts[p].head(dim);
  return X;
}

}  // namespace

const ShapeTable& validity_samples(ElementType type, int order) {
  static std::mutex mutex;
  static std::map<std::pair<ElementType, int>, std::unique_ptr<ShapeTable>> cache;
  std::lock_guard lock(mutex);
  auto& slot = cache[{type, order}];
  if (!slot) {
    const auto& rule = quadrature_rule(type, metric_quadrature_degree(type, order));
    const auto& nodes = reference_element(type, order).nodes;
    // det A is constant on linear simplices; elsewhere add the order-2p lattice.
    const bool dense = order > 1 || !is_simplex(type);
    const Eigen::MatrixXd extra = dense ? lattice(type, 2 * order) : Eigen::MatrixXd(nodes.rows(), 0);
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
// rule's, the nodes' where the lattice misses them, the lattice's): the Jacobians of a grid by
// sum factorization cost O(m P^d + ... + m^d P) instead of O(m^d P^d) (a P3 hexahedron: 8× less).
struct TensorSamples {
  const TensorBasis* basis = nullptr;  // null: dense samples only
  struct Grid {
    int m = 0;
    Eigen::MatrixXd B, D;  // m × P, TensorBasis::tabulate
  };
  std::vector<Grid> grids;
};

// Sorted distinct coordinates of row 0 of `points`, if the columns are exactly their tensor
// grid (dim copies); empty otherwise.
std::vector<double> grid_coordinates(const Eigen::MatrixXd& points) {
  std::vector<double> xs(points.row(0).begin(), points.row(0).end());
  std::sort(xs.begin(), xs.end());
  xs.erase(std::unique(xs.begin(), xs.end()), xs.end());
  std::vector<std::vector<double>> cols;
  for (Eigen::Index q = 0; q < points.cols(); ++q) {
    cols.emplace_back(points.col(q).begin(), points.col(q).end());
    for (double v : cols.back())
      if (!std::binary_search(xs.begin(), xs.end(), v)) return {};
  }
  std::sort(cols.begin(), cols.end());
  const bool distinct = std::adjacent_find(cols.begin(), cols.end()) == cols.end();
  // Distinct points on the grid, as many as it has: all of it.
  if (!distinct || std::lround(std::pow(double(xs.size()), double(points.rows()))) != points.cols()) return {};
  return xs;
}

// Largest 1D sizes the stack buffers of tensor_min_det take (orders ≤ 4, lattice 2p + 1).
constexpr int k_max_P = 5, k_max_m = 9;

const TensorSamples& tensor_samples(ElementType type, int order) {
  static std::mutex mutex;
  static std::map<std::pair<ElementType, int>, std::unique_ptr<TensorSamples>> cache;
  std::lock_guard lock(mutex);
  auto& slot = cache[{type, order}];
  if (slot) return *slot;
  slot = std::make_unique<TensorSamples>();
  const TensorBasis& basis = tensor_basis(type, order);
  if (basis.P == 0 || basis.P > k_max_P) return *slot;
  const std::vector<double> rule = grid_coordinates(quadrature_rule(type, metric_quadrature_degree(type, order)).points);
  std::vector<double> lattice;
  for (int i = 0; i <= 2 * order; ++i) lattice.push_back(2.0 * i / (2 * order) - 1.0);
  std::vector<std::vector<double>> sets = {rule, lattice};
  const bool nodes_on_lattice = std::all_of(basis.nodes.begin(), basis.nodes.end(), [&](double v) {
    return std::any_of(lattice.begin(), lattice.end(), [&](double l) { return std::abs(l - v) < 1e-14; });
  });
  if (!nodes_on_lattice) sets.push_back(basis.nodes);
  for (const auto& x : sets)
    if (x.empty() || static_cast<int>(x.size()) > k_max_m) return *slot;
  for (const auto& x : sets) {
    TensorSamples::Grid g;
    g.m = static_cast<int>(x.size());
    basis.tabulate(x, g.B, g.D);
    slot->grids.push_back(std::move(g));
  }
  slot->basis = &basis;
  return *slot;
}

// min det A over a tensor grid, u the nodal coordinates in lattice order (u[k + d·lattice]):
// the reference gradients by three (two) 1D passes, the determinant per point.
template <int d>
double tensor_min_det(const TensorSamples::Grid& g, int P, const double* u) {
  const int m = g.m;
  const auto B = [&](int q, int i) { return g.B(q, i); };
  const auto D = [&](int q, int i) { return g.D(q, i); };
  double lowest = std::numeric_limits<double>::infinity();
  const auto take = [&](const Eigen::Matrix<double, d, d>& A) {
    const double det = A.determinant();
    lowest = det > -std::numeric_limits<double>::infinity() ? std::min(lowest, det) : -std::numeric_limits<double>::infinity();  // NaN
  };
  // x pass: a0 = Σ_i l_i u, a1 = Σ_i l_i' u, at (qx, lattice rest).
  constexpr int rest = d == 3 ? k_max_P * k_max_P : k_max_P;
  double a0[d * k_max_m * rest] = {}, a1[d * k_max_m * rest] = {};
  const int n_rest = d == 3 ? P * P : P;
  for (int r = 0; r < n_rest; ++r)
    for (int qx = 0; qx < m; ++qx)
      for (int ix = 0; ix < P; ++ix) {
        const double* ui = u + d * (ix + P * r);
        const double b = B(qx, ix), s = D(qx, ix);
        for (int k = 0; k < d; ++k) a0[k + d * (qx + m * r)] += b * ui[k], a1[k + d * (qx + m * r)] += s * ui[k];
      }
  if constexpr (d == 2) {
    for (int qy = 0; qy < m; ++qy)
      for (int qx = 0; qx < m; ++qx) {
        Eigen::Matrix2d A = Eigen::Matrix2d::Zero();
        for (int iy = 0; iy < P; ++iy)
          for (int k = 0; k < 2; ++k) A(k, 0) += B(qy, iy) * a1[k + 2 * (qx + m * iy)], A(k, 1) += D(qy, iy) * a0[k + 2 * (qx + m * iy)];
        take(A);
      }
  } else {
    // y pass at (qx, qy, iz): c00 = B B u, c01 = D(y) B(x) u, c10 = B(y) D(x) u.
    double c00[3 * k_max_m * k_max_m * k_max_P] = {}, c01[3 * k_max_m * k_max_m * k_max_P] = {},
           c10[3 * k_max_m * k_max_m * k_max_P] = {};
    for (int iz = 0; iz < P; ++iz)
      for (int qy = 0; qy < m; ++qy)
        for (int qx = 0; qx < m; ++qx) {
          const int o = 3 * (qx + m * (qy + m * iz));
          for (int iy = 0; iy < P; ++iy) {
            const int i = 3 * (qx + m * (iy + P * iz));
            const double b = B(qy, iy), s = D(qy, iy);
            for (int k = 0; k < 3; ++k) c00[o + k] += b * a0[i + k], c01[o + k] += s * a0[i + k], c10[o + k] += b * a1[i + k];
          }
        }
    for (int qz = 0; qz < m; ++qz)
      for (int qy = 0; qy < m; ++qy)
        for (int qx = 0; qx < m; ++qx) {
          Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
          for (int iz = 0; iz < P; ++iz) {
            const int o = 3 * (qx + m * (qy + m * iz));
            const double b = B(qz, iz), s = D(qz, iz);
            for (int k = 0; k < 3; ++k) A(k, 0) += b * c10[o + k], A(k, 1) += b * c01[o + k], A(k, 2) += s * c00[o + k];
          }
          take(A);
        }
  }
  return lowest;
}

template <int d>
double min_det_tensor(const TensorSamples& ts, const Eigen::MatrixXd& X) {
  const int P = ts.basis->P;
  double u[3 * k_max_P * k_max_P * k_max_P];
  for (std::size_t l = 0; l < ts.basis->node.size(); ++l)
    for (int k = 0; k < d; ++k) u[k + d * l] = X(k, ts.basis->node[l]);
  double m = std::numeric_limits<double>::infinity();
  for (const TensorSamples::Grid& g : ts.grids) m = std::min(m, tensor_min_det<d>(g, P, u));
  return m;
}

double min_det_samples(ElementType type, int order, const Eigen::MatrixXd& X, const std::vector<std::uint8_t>* skip) {
  if (!skip && X.rows() == topological_dim(type)) {
    const TensorSamples& ts = tensor_samples(type, order);
    if (ts.basis && X.rows() == 2) return min_det_tensor<2>(ts, X);
    if (ts.basis && X.rows() == 3) return min_det_tensor<3>(ts, X);
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
  return min_det_samples(type, order, X, nullptr);
}

double min_jacobian_det(ElementType type, int order, const Eigen::MatrixXd& X, const std::vector<std::uint8_t>& skip) {
  MESHMORPH_CHECK(skip.size() == static_cast<std::size_t>(validity_samples(type, order).n_points()),
                  "min_jacobian_det: one skip flag per validity sample");
  return min_det_samples(type, order, X, &skip);
}

std::size_t count_invalid_cells(const Mesh& mesh) {
  std::size_t bad = 0;
  for (const auto& b : mesh.cells) {
    const auto n = static_cast<std::int64_t>(b.n_cells());
#pragma omp parallel for reduction(+ : bad) schedule(static)
    for (std::int64_t c = 0; c < n; ++c) {
      const double det = min_jacobian_det(b.type, b.order, cell_coordinates(mesh, b, static_cast<std::size_t>(c)));
      if (!(det > 0) || !std::isfinite(det)) ++bad;
    }
  }
  return bad;
}

}  // namespace meshmorph
