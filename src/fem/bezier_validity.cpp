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

#include "meshmorph/error.h"
#include "meshmorph/fem/shape_table.h"
#include "meshmorph/fem/tensor_basis.h"
#include "meshmorph/fem/validity.h"

namespace meshmorph::detail {

double binomial(int n, int k) {
  double b = 1.0;
  for (int i = 1; i <= k; ++i) b = b * (n - k + i) / i;
  return b;
}

Eigen::MatrixXd segment_bernstein(int q) {
  Eigen::MatrixXd M(q + 1, q + 1);
  for (int i = 0; i <= q; ++i)
    for (int k = 0; k <= q; ++k) M(i, k) = binomial(q, k) * std::pow(double(i) / q, k) * std::pow(1.0 - double(i) / q, q - k);
  return M;
}

namespace {

// Degree of det A: each column of A has degree p − 1 (simplex, total degree) or p − 1 in its
// own variable and p in the others (tensor cell).
int det_degree(ElementType type, int order) {
  const int d = topological_dim(type);
  return is_simplex(type) ? d * (order - 1) : d * order - 1;
}

// The Bernstein expansion of degree q on (type)'s reference cell, from values at its lattice.
struct DetExpansion {
  int q = 0;
  Eigen::MatrixXd unit_lattice;   ///< dim × N: the lattice on the unit simplex or [0, 1]^d, x fastest
  Eigen::MatrixXd to_bernstein;   ///< simplices: N × N; tensor cells: (q+1) × (q+1), along each axis
  Eigen::MatrixXd from_bernstein; ///< its inverse: the Bernstein polynomials at the lattice
  std::vector<std::array<int, 4>> multi_index;  ///< simplices: α of each coefficient (α_0 = q − the rest)
  std::vector<Eigen::Index> slot;               ///< simplices: α_1 + (q+1)(α_2 + (q+1) α_3) → its index
  std::vector<Eigen::Index> corners;            ///< the coefficients at the cell's corners
  Eigen::Index index_of(const std::array<int, 4>& alpha) const {
    return slot[static_cast<std::size_t>(alpha[1] + (q + 1) * (alpha[2] + (q + 1) * alpha[3]))];
  }
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
    e->from_bernstein = M;
    e->slot.assign(static_cast<std::size_t>(std::lround(std::pow(q + 1, dim))), -1);
    for (Eigen::Index a = 0; a < n; ++a) {
      std::array<int, 4> alpha{q, 0, 0, 0};
      for (int k = 0; k < dim; ++k) {
        alpha[static_cast<std::size_t>(k + 1)] = static_cast<int>(std::lround(e->unit_lattice(k, a) * q));
        alpha[0] -= alpha[static_cast<std::size_t>(k + 1)];
      }
      e->multi_index.push_back(alpha);
      e->slot[static_cast<std::size_t>(alpha[1] + (q + 1) * (alpha[2] + (q + 1) * alpha[3]))] = a;
      if (*std::max_element(alpha.begin(), alpha.end()) == q) e->corners.push_back(a);
    }
  } else {
    const Eigen::MatrixXd M = segment_bernstein(q);
    e->to_bernstein = M.inverse();
    e->from_bernstein = M;
    for (Eigen::Index a = 0; a < n; ++a) {
      bool corner = true;
      for (Eigen::Index k = 0, rest = a; k < topological_dim(type); ++k, rest /= q + 1) corner = corner && (rest % (q + 1) == 0 || rest % (q + 1) == q);
      if (corner) e->corners.push_back(a);
    }
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

template <int d>
void lattice_dets(const DetExpansion& e, bool simplex, const Eigen::MatrixXd& X, Eigen::VectorXd& v) {
  if (simplex) dets_at<d>(e.table, X, v);
  else dets_on_grid<d>(e.grid, X, v);
}

// The Bernstein coefficients of the values v at the lattice.
Eigen::VectorXd coefficients(const DetExpansion& e, int dim, bool simplex, const Eigen::VectorXd& v) {
  if (simplex) return e.to_bernstein * v;
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
  return c;
}

// The value at lattice point i of a piece whose coefficients are c: the Bernstein polynomials
// at the lattice (from_bernstein), contracted axis by axis on a tensor cell.
double value_at(const DetExpansion& e, int dim, bool simplex, const Eigen::VectorXd& c, Eigen::Index i) {
  if (simplex) return e.from_bernstein.row(i).dot(c);
  const int m = e.q + 1;
  Eigen::VectorXd line = c;
  for (int axis = dim - 1; axis >= 0; --axis) {  // contract the slowest axis first
    const Eigen::Index block = line.size() / m, ia = (i / static_cast<Eigen::Index>(std::lround(std::pow(m, axis)))) % m;
    Eigen::VectorXd next = Eigen::VectorXd::Zero(block);
    for (int k = 0; k < m; ++k) next += e.from_bernstein(ia, k) * line.segment(k * block, block);
    line.swap(next);
  }
  return line(0);
}

// A piece of the reference cell: a simplex (its dim + 1 vertices as columns) or a box (its
// lower and upper corners), both in reference coordinates, with the Bernstein coefficients of
// det A on it.
struct Piece {
  Eigen::MatrixXd corners;
  Eigen::VectorXd c;
  int depth = 0;
};

// The two halves of a piece, split across its longest edge (side), their coefficients by de
// Casteljau's algorithm at 1/2 along each line of coefficients that runs across the split:
// on a simplex split across edge ab, the multi-indices with the others fixed and α_a + α_b = s;
// on a box, the lines along the split axis.
std::array<Piece, 2> halves(const DetExpansion& e, bool simplex, const Piece& s) {
  std::array<Piece, 2> h{s, s};
  h[0].depth = h[1].depth = s.depth + 1;
  Eigen::Index a = 0, b = 1, stride = 1;
  if (simplex) {
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
    for (Eigen::Index k = 0; k < axis; ++k) stride *= e.q + 1;
  }
  thread_local std::vector<Eigen::Index> line;
  thread_local std::vector<double> w;
  for (Eigen::Index i = 0; i < s.c.size(); ++i) {
    line.clear();
    if (simplex) {  // i starts a line where α_b = 0; its members step one unit from a to b
      const auto& alpha = e.multi_index[static_cast<std::size_t>(i)];
      if (alpha[static_cast<std::size_t>(b)] != 0) continue;
      auto beta = alpha;
      for (int j = 0; j <= alpha[static_cast<std::size_t>(a)]; ++j, --beta[static_cast<std::size_t>(a)], ++beta[static_cast<std::size_t>(b)])
        line.push_back(e.index_of(beta));
    } else {
      if ((i / stride) % (e.q + 1) != 0) continue;
      for (int j = 0; j <= e.q; ++j) line.push_back(i + j * stride);
    }
    w.resize(line.size());
    for (std::size_t j = 0; j < line.size(); ++j) w[j] = s.c(line[j]);
    const std::size_t n = line.size() - 1;
    h[0].c(line[0]) = w[0];
    h[1].c(line[n]) = w[n];
    for (std::size_t r = 1; r <= n; ++r) {
      for (std::size_t j = 0; j + r <= n; ++j) w[j] = 0.5 * (w[j] + w[j + 1]);
      h[0].c(line[r]) = w[0];
      h[1].c(line[n - r]) = w[n - r];
    }
  }
  return h;
}

// The least det A that a piece's coefficients show: the lowest coefficient at a corner of the
// piece (exactly det A there), else det A at the lattice point of the lowest coefficient when
// that coefficient is ≤ 0; +inf when neither is ≤ 0.
double negative_value(const DetExpansion& e, int dim, bool simplex, const Eigen::VectorXd& c) {
  double corner = std::numeric_limits<double>::infinity();
  for (const Eigen::Index i : e.corners) corner = std::min(corner, c(i));
  if (corner <= 0.0) return corner;
  Eigen::Index at = 0;
  if (c.minCoeff(&at) > 0.0) return std::numeric_limits<double>::infinity();
  const double value = value_at(e, dim, simplex, c, at);
  return value <= 0.0 ? value : std::numeric_limits<double>::infinity();
}

// `piece`, where given, receives the corners of the piece where det A ≤ 0 was found.
template <int d>
double bezier_min_det_dim(ElementType type, int order, const Eigen::MatrixXd& X, double sampled, Eigen::MatrixXd* piece) {
  const DetExpansion& e = expansion(type, order);
  const bool simplex = is_simplex(type);
  Piece root;
  root.corners = simplex ? Eigen::MatrixXd(d, d + 1) : Eigen::MatrixXd(d, 2);
  if (simplex) root.corners << Eigen::MatrixXd::Zero(d, 1), Eigen::MatrixXd::Identity(d, d);
  else root.corners << -Eigen::VectorXd::Ones(d), Eigen::VectorXd::Ones(d);
  Eigen::VectorXd v;
  lattice_dets<d>(e, simplex, X, v);
  if (v.minCoeff() <= 0.0) {
    if (piece) *piece = root.corners;
    return v.minCoeff();
  }
  root.c = coefficients(e, d, simplex, v);
  if (root.c.minCoeff() > 0.0) return sampled;
  // Undecided: halve and look again. 6d halvings make a piece 2^−6 of the cell in each
  // direction, where the coefficients are within 1/4096 of the values (O(h²)); the budget
  // bounds a cell whose det A touches zero without crossing it.
  constexpr int k_max_depth = 6 * d, k_budget = 2048;
  std::vector<Piece> stack{root};
  for (int examined = 0; !stack.empty() && examined < k_budget;) {
    const Piece s = stack.back();
    stack.pop_back();
    if (s.depth >= k_max_depth) continue;  // undecided at the finest level: as sampling said
    for (Piece& h : halves(e, simplex, s)) {
      ++examined;
      if (const double value = negative_value(e, d, simplex, h.c); value <= 0.0) {
        if (piece) *piece = h.corners;
        return value;
      }
      if (h.c.minCoeff() <= 0.0) stack.push_back(std::move(h));
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
        if (type == ElementType::Prism ? i + j <= m : (!is_simplex(type) || i + j + k <= m)) pts.emplace_back(double(i) / m, double(j) / m, double(k) / m);
  if (type == ElementType::Pyramid) {  // (u, v, ζ) of [0, 1]³ → (ξ, η, ζ), below the apex
    std::vector<Eigen::Vector3d> below;
    for (const Eigen::Vector3d& p : pts)
      if (p(2) < 1.0) below.emplace_back((2 * p(0) - 1) * (1 - p(2)), (2 * p(1) - 1) * (1 - p(2)), p(2));
    pts.swap(below);
  }
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
  if (type == ElementType::Prism || type == ElementType::Pyramid) return false;  // prism_min_det, pyramid_min_det
  if (is_simplex(type)) return order > 1;
  return !(type == ElementType::Quadrilateral && order == 1);
}

Eigen::VectorXd det_bernstein_coefficients(ElementType type, int order, const Eigen::MatrixXd& X) {
  const int dim = topological_dim(type);
  MESHMORPH_CHECK(X.rows() == dim && det_needs_bounds(type, order), "det_bernstein_coefficients: a curved cell in its own dimension");
  const DetExpansion& e = expansion(type, order);
  Eigen::VectorXd v;
  if (dim == 2) lattice_dets<2>(e, is_simplex(type), X, v);
  else lattice_dets<3>(e, is_simplex(type), X, v);
  return coefficients(e, dim, is_simplex(type), v);
}

double bezier_min_det(ElementType type, int order, const Eigen::MatrixXd& X, double sampled) {
  const int dim = topological_dim(type);
  if (type == ElementType::Prism && X.rows() == 3) return prism_min_det(order, X, sampled);
  if (type == ElementType::Pyramid && order == 1) return sampled;  // exact at the base corners: pyramid_min_det
  if (type == ElementType::Pyramid && X.rows() == 3) return pyramid_bounds_min_det(order, X, sampled);
  if (X.rows() != dim || !det_needs_bounds(type, order)) return sampled;
  return dim == 2 ? bezier_min_det_dim<2>(type, order, X, sampled, nullptr) : bezier_min_det_dim<3>(type, order, X, sampled, nullptr);
}

}  // namespace meshmorph::detail

namespace meshmorph {

Eigen::MatrixXd fold_samples(ElementType type, int order, const Eigen::MatrixXd& X) {
  const int dim = topological_dim(type);
  if (X.rows() != dim || !detail::det_needs_bounds(type, order)) return Eigen::MatrixXd(dim, 0);
  Eigen::MatrixXd piece;
  const double sampled = std::numeric_limits<double>::infinity();
  const double value = dim == 2 ? detail::bezier_min_det_dim<2>(type, order, X, sampled, &piece)
                                : detail::bezier_min_det_dim<3>(type, order, X, sampled, &piece);
  if (!(value <= 0.0)) return Eigen::MatrixXd(dim, 0);
  // The piece's lattice of the degree of det A (whose values there give its coefficients on
  // the piece): a simplex piece maps the unit lattice barycentrically, a box piece from its
  // lower to its upper corner.
  const Eigen::MatrixXd unit = detail::unit_lattice(type, detail::det_degree(type, order));
  Eigen::MatrixXd points(dim, unit.cols());
  for (Eigen::Index i = 0; i < unit.cols(); ++i) {
    if (is_simplex(type)) {
      points.col(i) = piece.col(0);
      for (int k = 0; k < dim; ++k) points.col(i) += unit(k, i) * (piece.col(k + 1) - piece.col(0));
    } else {
      points.col(i) = piece.col(0) + (piece.col(1) - piece.col(0)).cwiseProduct(unit.col(i));
    }
  }
  return points;
}

}  // namespace meshmorph
