// SPDX-License-Identifier: MIT
#include "fem/detail/bezier_validity.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <vector>

#include <Eigen/LU>

#include "meshmorph/fem/shape_table.h"
#include "meshmorph/fem/tensor_basis.h"

namespace meshmorph::detail {
namespace {

// Degree of det A: each column of A has degree p − 1 (simplex, total degree) or p − 1 in its
// own variable and p in the others (tensor cell).
int det_degree(ElementType type, int order) {
  const int d = topological_dim(type);
  return is_simplex(type) ? d * (order - 1) : d * order - 1;
}

double binomial(int n, int k) {
  double b = 1.0;
  for (int i = 1; i <= k; ++i) b = b * (n - k + i) / i;
  return b;
}

// The Bernstein expansion of degree q on (type)'s reference cell, from values at its lattice.
struct DetExpansion {
  int q = 0;
  Eigen::MatrixXd unit_lattice;   ///< dim × N: the lattice on the unit simplex or [0, 1]^d, x fastest
  Eigen::MatrixXd to_bernstein;   ///< simplices: N × N; tensor cells: (q+1) × (q+1), along each axis
  ShapeTable table;               ///< simplices: (type, order) at the lattice of the reference cell
  TensorGrid grid;                ///< tensor cells: the lattice as a grid (sum factorization)
};

std::unique_ptr<DetExpansion> make_expansion(ElementType type, int order) {
  auto e = std::make_unique<DetExpansion>();
  const int q = e->q = det_degree(type, order);
  e->unit_lattice = unit_lattice(type, q);
  const auto n = e->unit_lattice.cols();
  if (is_simplex(type)) {
    e->table = tabulate(type, order, e->unit_lattice);
    // M(i, α) = B_α(λ_i), λ_i = α_i / q: the Bernstein polynomials at the lattice points.
    const int dim = topological_dim(type);
    Eigen::MatrixXd M(n, n);
    for (Eigen::Index i = 0; i < n; ++i) {
      Eigen::VectorXd lambda(dim + 1);
      lambda(0) = 1.0 - e->unit_lattice.col(i).sum();
      lambda.tail(dim) = e->unit_lattice.col(i);
      for (Eigen::Index a = 0; a < n; ++a) {
        const Eigen::VectorXd alpha_tail = (e->unit_lattice.col(a) * q).array().round();
        double b = 1.0;
        int left = q;
        for (int k = 0; k < dim; ++k) {
          const int ak = static_cast<int>(alpha_tail(k));
          b *= binomial(left, ak) * std::pow(lambda(k + 1), ak);
          left -= ak;
        }
        M(i, a) = b * std::pow(lambda(0), left);
      }
    }
    e->to_bernstein = M.inverse();
  } else {
    Eigen::MatrixXd M(q + 1, q + 1);
    for (int i = 0; i <= q; ++i)
      for (int k = 0; k <= q; ++k) M(i, k) = binomial(q, k) * std::pow(double(i) / q, k) * std::pow(1.0 - double(i) / q, q - k);
    e->to_bernstein = M.inverse();
    std::vector<double> x;
    for (int i = 0; i <= q; ++i) x.push_back(2.0 * i / q - 1.0);
    e->grid = tensor_grid(type, order, x);
  }
  return e;
}

const DetExpansion& expansion(ElementType type, int order) {
  static std::mutex mutex;
  static std::map<std::pair<ElementType, int>, std::unique_ptr<DetExpansion>> cache;
  std::lock_guard lock(mutex);
  auto& slot = cache[{type, order}];
  if (!slot) slot = make_expansion(type, order);
  return *slot;
}

// det A at the points of a table (NaN as −∞).
template <int d>
void dets_at(const ShapeTable& t, const Eigen::MatrixXd& X, Eigen::VectorXd& v) {
  v.resize(t.n_points());
  for (int p = 0; p < t.n_points(); ++p) {
    const double det = Eigen::Matrix<double, d, d>(X.lazyProduct(t.grad(p))).determinant();
    v(p) = det > -std::numeric_limits<double>::infinity() ? det : -std::numeric_limits<double>::infinity();
  }
}

// Least Bernstein coefficient of the values v at the lattice.
double least_coefficient(const DetExpansion& e, int dim, bool simplex, const Eigen::VectorXd& v) {
  if (simplex) return (e.to_bernstein * v).minCoeff();
  // Along each axis in turn (the lattice index is i_0 + m (i_1 + m i_2), m = q + 1).
  const int m = e.q + 1;
  Eigen::VectorXd c = v, next(v.size());
  Eigen::Index stride = 1;
  for (int axis = 0; axis < dim; ++axis, stride *= m) {
    for (Eigen::Index base = 0; base < c.size(); ++base) {
      if ((base / stride) % m != 0) continue;  // the first point of each line along `axis`
      for (int i = 0; i < m; ++i) {
        double sum = 0.0;
        for (int k = 0; k < m; ++k) sum += e.to_bernstein(i, k) * c(base + k * stride);
        next(base + i * stride) = sum;
      }
    }
    c.swap(next);
  }
  return c.minCoeff();
}

// A piece of the reference cell: a simplex (its dim + 1 vertices as columns) or a box (its
// lower and upper corners), both in reference coordinates.
struct Piece {
  Eigen::MatrixXd corners;
  int depth = 0;
};

Eigen::MatrixXd piece_points(bool simplex, const Piece& s, const Eigen::MatrixXd& unit) {
  if (simplex) {
    const Eigen::MatrixXd B = s.corners.rightCols(s.corners.cols() - 1).colwise() - s.corners.col(0);
    return (B * unit).colwise() + s.corners.col(0);
  }
  return ((s.corners.col(1) - s.corners.col(0)).asDiagonal() * unit).colwise() + s.corners.col(0);
}

// The two halves of a piece, split across its longest edge (side).
std::array<Piece, 2> halves(bool simplex, const Piece& s) {
  std::array<Piece, 2> h{s, s};
  h[0].depth = h[1].depth = s.depth + 1;
  if (simplex) {
    Eigen::Index a = 0, b = 1;
    double longest = -1.0;
    for (Eigen::Index i = 0; i < s.corners.cols(); ++i)
      for (Eigen::Index j = i + 1; j < s.corners.cols(); ++j)
        if (const double l = (s.corners.col(i) - s.corners.col(j)).squaredNorm(); l > longest) longest = l, a = i, b = j;
    const Eigen::VectorXd mid = 0.5 * (s.corners.col(a) + s.corners.col(b));
    h[0].corners.col(b) = mid;
    h[1].corners.col(a) = mid;
  } else {
    Eigen::Index axis = 0;
    (s.corners.col(1) - s.corners.col(0)).maxCoeff(&axis);
    const double mid = 0.5 * (s.corners(axis, 0) + s.corners(axis, 1));
    h[0].corners(axis, 1) = mid;
    h[1].corners(axis, 0) = mid;
  }
  return h;
}

template <int d>
double bezier_min_det_dim(ElementType type, int order, const Eigen::MatrixXd& X, double sampled) {
  const DetExpansion& e = expansion(type, order);
  const bool simplex = is_simplex(type);
  Eigen::VectorXd v;
  if (simplex) dets_at<d>(e.table, X, v);
  else dets_on_grid<d>(e.grid, X, v);
  if (v.minCoeff() <= 0.0) return v.minCoeff();
  if (least_coefficient(e, d, simplex, v) > 0.0) return sampled;
  // Undecided: halve and look again. 6d halvings make a piece 2^−6 of the cell in each
  // direction, where the coefficients are within 1/4096 of the values (O(h²)); the budget
  // bounds a cell whose det A touches zero without crossing it.
  constexpr int k_max_depth = 6 * d, k_budget = 2048;
  Piece root;
  root.corners = simplex ? Eigen::MatrixXd(d, d + 1) : Eigen::MatrixXd(d, 2);
  if (simplex) root.corners << Eigen::MatrixXd::Zero(d, 1), Eigen::MatrixXd::Identity(d, d);
  else root.corners << -Eigen::VectorXd::Ones(d), Eigen::VectorXd::Ones(d);
  std::vector<Piece> stack{root};
  for (int examined = 0; !stack.empty() && examined < k_budget;) {
    const Piece s = stack.back();
    stack.pop_back();
    if (s.depth >= k_max_depth) continue;  // undecided at the finest level: as sampling said
    for (const Piece& h : halves(simplex, s)) {
      ++examined;
      dets_at<d>(tabulate(type, order, piece_points(simplex, h, e.unit_lattice)), X, v);
      if (v.minCoeff() <= 0.0) return v.minCoeff();
      if (least_coefficient(e, d, simplex, v) <= 0.0) stack.push_back(h);
    }
  }
  return sampled;
}

}  // namespace

Eigen::MatrixXd unit_lattice(ElementType type, int m) {
  const int dim = topological_dim(type);
  std::vector<Eigen::Vector3d> pts;
  for (int k = 0; k <= (dim > 2 ? m : 0); ++k)
    for (int j = 0; j <= m; ++j)
      for (int i = 0; i <= m; ++i)
        if (!is_simplex(type) || i + j + k <= m) pts.emplace_back(double(i) / m, double(j) / m, double(k) / m);
  Eigen::MatrixXd X(dim, static_cast<Eigen::Index>(pts.size()));
  for (std::size_t p = 0; p < pts.size(); ++p) X.col(static_cast<Eigen::Index>(p)) = pts[p].head(dim);
  return X;
}

template <int d>
void dets_on_grid(const TensorGrid& g, const Eigen::MatrixXd& X, Eigen::VectorXd& v) {
  const int points = static_cast<int>(std::lround(std::pow(g.m, d)));
  thread_local std::vector<double> G;
  G.resize(static_cast<std::size_t>(d * d * points));
  grid_gradients(g, X.data(), d, G.data());
  v.resize(points);
  for (int p = 0; p < points; ++p) {
    const double det = Eigen::Map<const Eigen::Matrix<double, d, d>>(G.data() + d * d * p).determinant();
    v(p) = det > -std::numeric_limits<double>::infinity() ? det : -std::numeric_limits<double>::infinity();
  }
}

template void dets_on_grid<2>(const TensorGrid&, const Eigen::MatrixXd&, Eigen::VectorXd&);
template void dets_on_grid<3>(const TensorGrid&, const Eigen::MatrixXd&, Eigen::VectorXd&);

bool det_needs_bounds(ElementType type, int order) {
  if (is_simplex(type)) return order > 1;
  return !(type == ElementType::Quadrilateral && order == 1);
}

double bezier_min_det(ElementType type, int order, const Eigen::MatrixXd& X, double sampled) {
  const int dim = topological_dim(type);
  if (X.rows() != dim || !det_needs_bounds(type, order)) return sampled;
  return dim == 2 ? bezier_min_det_dim<2>(type, order, X, sampled) : bezier_min_det_dim<3>(type, order, X, sampled);
}

}  // namespace meshmorph::detail
