// SPDX-License-Identifier: MIT
// φ in monomials: one pass over at most 25 terms gives φ, ∂φ and ∂²φ with no allocation (the
// Lagrange form needs the basis's values, gradients and Hessians as heap matrices, then a
// product with the nodes). Closest points: Newton on |φ(u) − x|² with the exact Hessian, the
// reference domain's boundary handled by clipping and then Newton along its edges.
#include "geometry/detail/polynomial_facet.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <mutex>
#include <utility>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <Eigen/LU>

namespace meshmorph::detail {

using Terms = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 25, 1>;

struct FacetShape {
  ElementType type = ElementType::Line;
  int m = 1, order = 1, n_corners = 2;
  std::vector<std::array<int, 2>> exponents;  // μ_k = u^a v^b
  Eigen::MatrixXd to_monomial, to_bezier;     // n × n: coefficients = nodes · to_…
  Eigen::MatrixXd samples;                    // m × s: 2p + 1 per direction
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 2, 4> corners;  // m × n_corners
  std::array<std::vector<int>, 4> edge_controls;  // the control points of reference edge (corner k, k + 1)
};

namespace {

// The monomials LagrangeBasis spans: total degree ≤ p on lines and triangles, ≤ p in each
// variable on quadrilaterals.
std::vector<std::array<int, 2>> exponents(ElementType type, int p) {
  std::vector<std::array<int, 2>> out;
  for (int b = 0; b <= (type == ElementType::Line ? 0 : p); ++b)
    for (int a = 0; a <= (type == ElementType::Triangle ? p - b : p); ++a) out.push_back({a, b});
  return out;
}

double binomial(int n, int k) {
  double c = 1.0;
  for (int i = 1; i <= k; ++i) c = c * (n - k + i) / i;
  return c;
}

// The Bernstein polynomials of degree p at u: on [−1, 1] (lines, and quadrilaterals by
// products) and on the unit triangle (barycentric 1 − u − v, u, v). Their order: that of
// bernstein_points.
Eigen::VectorXd bernstein(ElementType type, int p, const Eigen::VectorXd& u) {
  auto line = [p](double s, int i) {
    const double t = 0.5 * (s + 1.0);
    return binomial(p, i) * std::pow(t, i) * std::pow(1.0 - t, p - i);
  };
  std::vector<double> b;
  if (type == ElementType::Line) {
    for (int i = 0; i <= p; ++i) b.push_back(line(u[0], i));
  } else if (type == ElementType::Quadrilateral) {
    for (int j = 0; j <= p; ++j)
      for (int i = 0; i <= p; ++i) b.push_back(line(u[0], i) * line(u[1], j));
  } else {
    const double l0 = 1.0 - u[0] - u[1];
    for (int j = 0; j <= p; ++j)
      for (int i = 0; i + j <= p; ++i)
        b.push_back(binomial(p, i) * binomial(p - i, j) * std::pow(u[0], i) * std::pow(u[1], j) * std::pow(l0, p - i - j));
  }
  return Eigen::Map<Eigen::VectorXd>(b.data(), static_cast<Eigen::Index>(b.size()));
}

// The domain point of each Bernstein polynomial (where it peaks), m × n.
Eigen::MatrixXd bernstein_points(ElementType type, int p) {
  std::vector<Eigen::Vector2d> u;
  for (int j = 0; j <= (type == ElementType::Line ? 0 : p); ++j)
    for (int i = 0; i <= (type == ElementType::Triangle ? p - j : p); ++i)
      u.push_back(type == ElementType::Triangle ? Eigen::Vector2d(double(i) / p, double(j) / p)
                                                : Eigen::Vector2d(2.0 * i / p - 1.0, 2.0 * j / p - 1.0));
  const int m = type == ElementType::Line ? 1 : 2;
  Eigen::MatrixXd out(m, static_cast<Eigen::Index>(u.size()));
  for (std::size_t k = 0; k < u.size(); ++k) out.col(static_cast<Eigen::Index>(k)) = u[k].head(m);
  return out;
}

// A lattice of 2p + 1 points per direction on the reference facet.
Eigen::MatrixXd sample_parameters(ElementType type, int order) {
  const int k = 2 * order;
  std::vector<Eigen::VectorXd> u;
  if (type == ElementType::Line) {
    for (int i = 0; i <= k; ++i) u.push_back(Eigen::VectorXd::Constant(1, -1.0 + 2.0 * i / k));
  } else {
    for (int j = 0; j <= k; ++j)
      for (int i = 0; i <= k; ++i) {
        if (type == ElementType::Triangle && i + j > k) continue;
        u.push_back(type == ElementType::Triangle ? Eigen::Vector2d(double(i) / k, double(j) / k)
                                                  : Eigen::Vector2d(-1.0 + 2.0 * i / k, -1.0 + 2.0 * j / k));
      }
  }
  Eigen::MatrixXd out(u.front().size(), static_cast<Eigen::Index>(u.size()));
  for (std::size_t i = 0; i < u.size(); ++i) out.col(static_cast<Eigen::Index>(i)) = u[i];
  return out;
}

std::unique_ptr<FacetShape> make_shape(const LagrangeBasis& basis) {
  auto s = std::make_unique<FacetShape>();
  s->type = basis.type();
  s->m = basis.dim();
  s->order = basis.order();
  s->n_corners = s->type == ElementType::Line ? 2 : s->type == ElementType::Triangle ? 3 : 4;
  s->exponents = exponents(s->type, s->order);
  const Eigen::MatrixXd& nodes = basis.reference().nodes;
  const auto n = nodes.cols();
  // Lagrange nodes X = coefficients · V with V(k, b) the k-th basis polynomial at node b.
  Eigen::MatrixXd V(n, n), Bz(n, n);
  for (Eigen::Index b = 0; b < n; ++b) {
    for (Eigen::Index k = 0; k < n; ++k) {
      const auto [e0, e1] = s->exponents[static_cast<std::size_t>(k)];
      V(k, b) = std::pow(nodes(0, b), e0) * (s->m > 1 ? std::pow(nodes(1, b), e1) : 1.0);
    }
    Bz.col(b) = bernstein(s->type, s->order, nodes.col(b));
  }
  s->to_monomial = V.fullPivLu().inverse();
  s->to_bezier = Bz.fullPivLu().inverse();
  s->samples = sample_parameters(s->type, s->order);
  s->corners = nodes.leftCols(s->n_corners);
  // A patch's boundary curve is the Bézier curve of its control points there.
  const Eigen::MatrixXd points = bernstein_points(s->type, s->order);
  for (int k = 0; k < s->n_corners && s->m == 2; ++k) {
    const Eigen::Vector2d a = s->corners.col(k), e = Eigen::Vector2d(s->corners.col((k + 1) % s->n_corners)) - a;
    for (Eigen::Index c = 0; c < points.cols(); ++c) {
      const Eigen::Vector2d v = Eigen::Vector2d(points.col(c)) - a;
      if (std::abs(v[0] * e[1] - v[1] * e[0]) <= 1e-12) s->edge_controls[static_cast<std::size_t>(k)].push_back(static_cast<int>(c));
    }
  }
  return s;
}

// The shared shape of (type, order).
const FacetShape& facet_shape(const LagrangeBasis& basis) {
  static std::mutex mutex;
  static std::map<std::pair<ElementType, int>, std::unique_ptr<FacetShape>> cache;
  std::lock_guard lock(mutex);
  std::unique_ptr<FacetShape>& slot = cache[{basis.type(), basis.order()}];
  if (!slot) slot = make_shape(basis);
  return *slot;
}

Eigen::Vector3d lift(const FacetVec& x) {
  Eigen::Vector3d y = Eigen::Vector3d::Zero();
  y.head(x.size()) = x;
  return y;
}

// The reference facet: [−1, 1] (lines), the unit triangle, [−1, 1]² (quadrilaterals).
FacetParam clip(ElementType type, FacetParam u) {
  if (type != ElementType::Triangle) return u.cwiseMax(-1.0).cwiseMin(1.0);
  u = u.cwiseMax(0.0);
  if (const double excess = u.sum() - 1.0; excess > 0.0) u = (u.array() - excess / 2).matrix().cwiseMax(0.0);
  return u / std::max(1.0, u.sum());
}

bool on_domain_boundary(ElementType type, const FacetParam& u) {
  constexpr double tol = 1e-12;
  if (type != ElementType::Triangle) return (u.cwiseAbs().array() >= 1.0 - tol).any();
  return (u.array() <= tol).any() || u.sum() >= 1.0 - tol;
}

}  // namespace

PolynomialFacet::PolynomialFacet(const LagrangeBasis& basis, const Eigen::MatrixXd& X, const std::array<bool, 4>& rim_edge,
                                 const std::array<bool, 4>& rim_corner)
    : shape_(&facet_shape(basis)), rim_edge_(rim_edge), rim_corner_(rim_corner) {
  const FacetShape& s = *shape_;
  origin_ = X.col(0);
  const Eigen::MatrixXd local = X.colwise() - X.col(0);
  C_ = local * s.to_monomial;
  samples_.resize(X.rows(), s.samples.cols());
  for (Eigen::Index k = 0; k < s.samples.cols(); ++k) samples_.col(k) = position(s.samples.col(k));
  // The hull of the control points holds the facet; lifted to 3D, relative to x₀.
  const Eigen::MatrixXd control = local * s.to_bezier;
  Eigen::Matrix3Xd P = Eigen::Matrix3Xd::Zero(3, control.cols());
  P.topRows(X.rows()) = control;
  const Eigen::Vector3d x0 = lift(origin_);
  // ≫ the rounding of the control points and of the planes' offsets, far from the origin too.
  const double pad = 1e-9 * ((P.rowwise().maxCoeff() - P.rowwise().minCoeff()).norm() + x0.norm());
  lo_ = x0 + P.rowwise().minCoeff() - Eigen::Vector3d::Constant(pad);
  hi_ = x0 + P.rowwise().maxCoeff() + Eigen::Vector3d::Constant(pad);
  for (std::size_t k = 0; k < s.edge_controls.size(); ++k) {
    const Eigen::Matrix3Xd E = P(Eigen::all, s.edge_controls[k]);
    if (E.cols() == 0) continue;
    edge_lo_[k] = x0 + E.rowwise().minCoeff() - Eigen::Vector3d::Constant(pad);
    edge_hi_[k] = x0 + E.rowwise().maxCoeff() + Eigen::Vector3d::Constant(pad);
  }
  auto add_plane = [&](Eigen::Vector3d a) {
    if (!(a.norm() > 0.0) || !a.allFinite()) return;  // a degenerate facet: the box alone
    a.normalize();
    normals_[static_cast<std::size_t>(n_planes_)] = a;
    offsets_[static_cast<std::size_t>(n_planes_++)] = a.dot(x0) + (a.transpose() * P).maxCoeff() + pad;
  };
  FacetParam mid(s.m);
  if (s.type == ElementType::Triangle) mid.setConstant(1.0 / 3.0);
  else mid.setZero();
  const FacetPoint c = evaluate(mid);
  const Eigen::Vector3d n0 = lift(unit_normal(c.T)), pc = lift(c.p);
  add_plane(n0);
  add_plane(-n0);
  for (int k = 0; k < s.n_corners && X.rows() == 3; ++k) {
    const Eigen::Vector3d a = lift(position(s.corners.col(k))), b = lift(position(s.corners.col((k + 1) % s.n_corners)));
    const Eigen::Vector3d e = (b - a).cross(n0);
    add_plane(e.dot(pc - a) > 0.0 ? Eigen::Vector3d(-e) : e);
  }
  if (X.rows() == 2) {
    const Eigen::Vector3d t = lift(position(s.corners.col(1))) - lift(position(s.corners.col(0)));
    add_plane(t);
    add_plane(-t);
  }
}

ElementType PolynomialFacet::type() const { return shape_->type; }

FacetPoint PolynomialFacet::evaluate(const FacetParam& u) const {
  const FacetShape& s = *shape_;
  const int m = s.m, p = s.order;
  // u_k^e and its first two derivatives in u_k, e ≤ p (the second axis 1, 0, 0 on lines).
  std::array<std::array<double, 5>, 2> P{}, D{}, DD{};
  for (int k = 0; k < 2; ++k) {
    P[k][0] = 1.0;
    for (int e = 1; e <= p && k < m; ++e) {
      P[k][e] = P[k][e - 1] * u[k];
      D[k][e] = e * P[k][e - 1];
      DD[k][e] = e * D[k][e - 1];
    }
  }
  const auto n = static_cast<Eigen::Index>(s.exponents.size());
  Terms mu(n), d0(n), d1(n), d00(n), d01(n), d11(n);
  for (Eigen::Index t = 0; t < n; ++t) {
    const auto [a, b] = s.exponents[static_cast<std::size_t>(t)];
    mu[t] = P[0][a] * P[1][b];
    d0[t] = D[0][a] * P[1][b];
    d1[t] = P[0][a] * D[1][b];
    d00[t] = DD[0][a] * P[1][b];
    d01[t] = D[0][a] * D[1][b];
    d11[t] = P[0][a] * DD[1][b];
  }
  FacetPoint q{s.type, u, origin_ + C_ * mu, FacetTangents(C_.rows(), m), FacetCurvature(C_.rows(), m * m)};
  q.T.col(0) = C_ * d0;
  q.S.col(0) = C_ * d00;
  if (m == 2) {
    q.T.col(1) = C_ * d1;
    q.S.col(1) = q.S.col(2) = C_ * d01;
    q.S.col(3) = C_ * d11;
  }
  return q;
}

FacetVec PolynomialFacet::position(const FacetParam& u) const {
  const FacetShape& s = *shape_;
  std::array<std::array<double, 5>, 2> P{};  // u_k^e, as in evaluate()
  for (int k = 0; k < 2; ++k) {
    P[k][0] = 1.0;
    for (int e = 1; e <= s.order && k < s.m; ++e) P[k][e] = P[k][e - 1] * u[k];
  }
  const auto n = static_cast<Eigen::Index>(s.exponents.size());
  Terms mu(n);
  for (Eigen::Index t = 0; t < n; ++t) mu[t] = P[0][s.exponents[static_cast<std::size_t>(t)][0]] * P[1][s.exponents[static_cast<std::size_t>(t)][1]];
  return origin_ + C_ * mu;
}

double PolynomialFacet::lower_bound2(const Eigen::Vector3d& x) const {
  double d2 = (x - x.cwiseMax(lo_).cwiseMin(hi_)).squaredNorm();
  for (int i = 0; i < n_planes_; ++i)
    if (const double v = normals_[static_cast<std::size_t>(i)].dot(x) - offsets_[static_cast<std::size_t>(i)]; v > 0.0)
      d2 = std::max(d2, v * v);
  return d2;
}

int PolynomialFacet::corner_at(const FacetParam& u) const {
  for (int c = 0; c < shape_->n_corners; ++c)
    if ((u - shape_->corners.col(c)).norm() <= 1e-12) return c;
  return -1;
}

// Newton on ½|φ(u(t)) − x|² along the reference segment u(t) = a + t(b − a), t ∈ [0, 1]
// (clipping is the exact constraint in one variable).
FacetPoint PolynomialFacet::closest_on_segment(const Eigen::VectorXd& x, const FacetParam& a, const FacetParam& b) const {
  const FacetParam e = b - a;
  const int m = static_cast<int>(e.size());
  double t = 0.5, best = std::numeric_limits<double>::infinity();
  for (double s : {0.0, 0.25, 0.5, 0.75, 1.0})
    if (const double r2 = (position(a + s * e) - x).squaredNorm(); r2 < best) best = r2, t = s;
  FacetPoint q = evaluate(a + t * e);
  for (int it = 0; it < 40; ++it) {
    const FacetVec r = x - q.p, pt = q.T * e;
    FacetVec ptt = FacetVec::Zero(x.size());
    for (int k = 0; k < m; ++k)
      for (int l = 0; l < m; ++l) ptt += e[k] * e[l] * q.S.col(k * m + l);
    double h = pt.squaredNorm() - r.dot(ptt);
    if (!(h > 0.0)) h = pt.squaredNorm();
    const double t_new = std::clamp(t + r.dot(pt) / h, 0.0, 1.0);
    const bool done = std::abs(t_new - t) <= 1e-14;  // quadratic: the next step is at rounding
    t = t_new;
    q = evaluate(a + t * e);
    if (done) break;
  }
  return q;
}

FacetHit PolynomialFacet::closest(const Eigen::VectorXd& x) const {
  const FacetShape& s = *shape_;
  const int m = s.m;
  Eigen::Index start = 0;
  double nearest = std::numeric_limits<double>::infinity();
  for (Eigen::Index k = 0; k < samples_.cols(); ++k)
    if (const double r2 = (samples_.col(k) - x).squaredNorm(); r2 < nearest) nearest = r2, start = k;
  FacetPoint q = evaluate(s.samples.col(start));
  // Newton with the exact Hessian G − Σ r_k ∂²φ_k (Gauss–Newton G where it is not positive).
  for (int it = 0; it < 40; ++it) {
    const FacetVec r = x - q.p;
    const FacetForm G = q.T.transpose() * q.T;
    FacetForm H = G;
    for (int k = 0; k < m; ++k)
      for (int l = 0; l < m; ++l) H(k, l) -= r.dot(q.S.col(k * m + l));
    Eigen::LLT<FacetForm> llt(H);
    if (llt.info() != Eigen::Success) llt.compute(G);
    const FacetParam u = clip(s.type, q.u + llt.solve(q.T.transpose() * r));
    const bool done = (u - q.u).norm() <= 1e-14;  // quadratic: the next step is at rounding
    q = evaluate(u);
    if (done) break;
  }
  FacetHit hit{(q.p - x).squaredNorm(), q, false};
  if (!on_domain_boundary(s.type, q.u)) return hit;
  if (m == 1) {
    const int c = corner_at(q.u);
    hit.rim = c >= 0 && rim_corner_[static_cast<std::size_t>(c)];
    return hit;
  }
  // The interior iteration stopped on ∂K: the minimum over each edge (and so its corners),
  // but an edge whose control points' box is farther than the nearest edge so far.
  hit.dist2 = std::numeric_limits<double>::infinity();
  const Eigen::Vector3d x3 = lift(x);
  for (int k = 0; k < s.n_corners; ++k) {
    const Eigen::Vector3d& lo = edge_lo_[static_cast<std::size_t>(k)];
    if ((x3 - x3.cwiseMax(lo).cwiseMin(edge_hi_[static_cast<std::size_t>(k)])).squaredNorm() > hit.dist2) continue;
    const FacetPoint e = closest_on_segment(x, s.corners.col(k), s.corners.col((k + 1) % s.n_corners));
    if (const double d2 = (e.p - x).squaredNorm(); d2 < hit.dist2) {
      const int c = corner_at(e.u);
      hit = {d2, e, c >= 0 ? rim_corner_[static_cast<std::size_t>(c)] : rim_edge_[static_cast<std::size_t>(k)]};
    }
  }
  return hit;
}

Eigen::MatrixXd shape_hessian(const FacetPoint& q, const Eigen::VectorXd& n, double sigma) {
  const int m = static_cast<int>(q.T.cols());
  const FacetForm G = q.T.transpose() * q.T;
  FacetForm B(m, m);
  for (int k = 0; k < m; ++k)
    for (int l = 0; l < m; ++l) B(k, l) = n.dot(q.S.col(k * m + l));
  const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 3, 3> H =
      -q.T * G.inverse() * B * (G - sigma * B).inverse() * q.T.transpose();
  return 0.5 * (H + H.transpose());
}

// Minimises ½|T du + g|² over K by its active sets (rows a of the active constraints a·du ≥ 0).
double cone_descent(const FacetPoint& q, const Eigen::VectorXd& g) {
  constexpr double tol = 1e-8;  // ε-active: as at a crease within 1e-8 of it (facet_surface.cpp)
  const int m = static_cast<int>(q.T.cols());
  std::array<FacetParam, 4> rows;
  int n_rows = 0;
  auto add = [&](const FacetParam& a) { rows[static_cast<std::size_t>(n_rows++)] = a; };
  if (q.type == ElementType::Triangle) {
    if (q.u[0] <= tol) add(Eigen::Vector2d(1.0, 0.0));
    if (q.u[1] <= tol) add(Eigen::Vector2d(0.0, 1.0));
    if (q.u.sum() >= 1.0 - tol) add(Eigen::Vector2d(-1.0, -1.0));
  } else {
    for (int k = 0; k < m; ++k) {
      if (q.u[k] >= 1.0 - tol) add(-FacetParam::Unit(m, k));
      if (q.u[k] <= -1.0 + tol) add(FacetParam::Unit(m, k));
    }
  }
  const FacetForm G = q.T.transpose() * q.T;
  const FacetParam b = -q.T.transpose() * g;
  auto feasible = [&](const FacetParam& du) {
    for (int i = 0; i < n_rows; ++i)
      if (rows[static_cast<std::size_t>(i)].dot(du) < -1e-12 * du.norm()) return false;
    return true;
  };
  // The minimiser on {du : a·du = 0} is du = Z (ZᵀGZ)⁻¹ Zᵀb, of objective −½ bᵀdu; du = 0 is always feasible.
  double best_objective = 0.0, descent = 0.0;
  auto offer = [&](const FacetForm& Z) {
    const FacetParam du = Z * (Z.transpose() * G * Z).ldlt().solve(Z.transpose() * b);
    if (du.allFinite() && feasible(du) && -0.5 * b.dot(du) < best_objective) {
      best_objective = -0.5 * b.dot(du);
      descent = (q.T * du).norm();
    }
  };
  offer(FacetForm::Identity(m, m));
  if (m == 2)
    for (int i = 0; i < n_rows; ++i) offer(Eigen::Vector2d(-rows[static_cast<std::size_t>(i)][1], rows[static_cast<std::size_t>(i)][0]));
  return descent;
}

}  // namespace meshmorph::detail
