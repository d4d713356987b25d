// SPDX-License-Identifier: MIT
// Closest points on a union of polynomial facets: Newton on |φ(u) − x|² in each candidate
// facet's reference domain (then on its edges when the interior iteration ends on one), the
// candidates from a bounding-box tree, pruned by the distance to their boxes.
#include "meshmorph/geometry/facet_surface.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <memory>
#include <numeric>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <Eigen/LU>

#include "geometry/detail/level_set_node.h"
#include "meshmorph/error.h"
#include "meshmorph/fem/lagrange_basis.h"
#include "meshmorph/fem/trace.h"

namespace meshmorph {

Eigen::VectorXd outward_normal(const Eigen::MatrixXd& T) {
  Eigen::VectorXd n(T.rows());
  if (T.rows() == 2) {
    n << T(1, 0), -T(0, 0);  // the cell is left of a line facet
  } else {
    n = Eigen::Vector3d(T.col(0)).cross(Eigen::Vector3d(T.col(1)));
  }
  return n.normalized();
}

namespace detail {
namespace {

struct Facet {
  const LagrangeBasis* basis = nullptr;
  Eigen::MatrixXd nodes;     // d × n, the facet element's ordering
  Eigen::MatrixXd samples;   // d × s: φ at the sample parameters of its (type, order)
  std::array<bool, 4> rim_edge{};    // 3D: reference edge (corner k, k + 1) has no neighbour in S
  std::array<bool, 4> rim_corner{};  // corner k is on such an edge (2D: has no neighbour)
  Eigen::Vector3d lo, hi;            // its box, enlarged (z = 0 in 2D)
};

// φ, ∂φ/∂u (d × m) and ∂²φ/∂u_k∂u_l (column k·m + l, d × m²) at u.
struct FacetPoint {
  ElementType type;
  Eigen::VectorXd u, p;
  Eigen::MatrixXd T, S;
};

FacetPoint evaluate(const Facet& f, const Eigen::VectorXd& u) {
  return {f.basis->type(), u, f.nodes * f.basis->values(u), f.nodes * f.basis->gradients(u), f.nodes * f.basis->hessians(u)};
}


// The reference facet: [−1, 1] (lines), the unit triangle, [−1, 1]² (quadrilaterals).
Eigen::VectorXd clip(ElementType type, Eigen::VectorXd u) {
  if (type != ElementType::Triangle) return u.cwiseMax(-1.0).cwiseMin(1.0);
  u = u.cwiseMax(0.0);
  if (const double excess = u.sum() - 1.0; excess > 0.0) u = (u.array() - excess / 2).matrix().cwiseMax(0.0);
  return u / std::max(1.0, u.sum());
}

bool on_domain_boundary(ElementType type, const Eigen::VectorXd& u) {
  constexpr double tol = 1e-12;
  if (type != ElementType::Triangle) return (u.cwiseAbs().array() >= 1.0 - tol).any();
  return (u.array() <= tol).any() || u.sum() >= 1.0 - tol;
}

struct Hit {
  double dist2 = std::numeric_limits<double>::infinity();
  FacetPoint at;
  bool rim = false;
};

// Newton on ½|φ(u(t)) − x|² along the reference segment u(t) = a + t(b − a), t ∈ [0, 1]
// (clipping is the exact constraint in one variable).
FacetPoint closest_on_segment(const Facet& f, const Eigen::VectorXd& x, const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  const Eigen::VectorXd e = b - a;
  const int m = static_cast<int>(e.size());
  double t = 0.5, best = std::numeric_limits<double>::infinity();
  for (double s : {0.0, 0.25, 0.5, 0.75, 1.0})
    if (const double r2 = (f.nodes * f.basis->values(a + s * e) - x).squaredNorm(); r2 < best) best = r2, t = s;
  FacetPoint q = evaluate(f, a + t * e);
  for (int it = 0; it < 40; ++it) {
    const Eigen::VectorXd r = x - q.p, pt = q.T * e;
    Eigen::VectorXd ptt = Eigen::VectorXd::Zero(x.size());
    for (int k = 0; k < m; ++k)
      for (int l = 0; l < m; ++l) ptt += e[k] * e[l] * q.S.col(k * m + l);
    double h = pt.squaredNorm() - r.dot(ptt);
    if (!(h > 0.0)) h = pt.squaredNorm();
    const double t_new = std::clamp(t + r.dot(pt) / h, 0.0, 1.0);
    const bool done = std::abs(t_new - t) <= 1e-14;  // quadratic: the next step is at rounding
    t = t_new;
    q = evaluate(f, a + t * e);
    if (done) break;
  }
  return q;
}

Hit closest_on_facet(const Facet& f, const Eigen::MatrixXd& params, const Eigen::VectorXd& x) {
  const ElementType type = f.basis->type();
  const int m = f.basis->dim();
  Eigen::Index start = 0;
  (f.samples.colwise() - x).colwise().squaredNorm().minCoeff(&start);
  FacetPoint q = evaluate(f, params.col(start));
  // Newton with the exact Hessian G − Σ r_k ∂²φ_k (Gauss–Newton G where it is not positive).
  for (int it = 0; it < 40; ++it) {
    const Eigen::VectorXd r = x - q.p;
    const Eigen::MatrixXd G = q.T.transpose() * q.T;
    Eigen::MatrixXd H = G;
    for (int k = 0; k < m; ++k)
      for (int l = 0; l < m; ++l) H(k, l) -= r.dot(q.S.col(k * m + l));
    Eigen::LLT<Eigen::MatrixXd> llt(H);
    if (llt.info() != Eigen::Success) llt.compute(G);
    const Eigen::VectorXd u = clip(type, q.u + llt.solve(q.T.transpose() * r));
    const bool done = (u - q.u).norm() <= 1e-14;  // quadratic: the next step is at rounding
    q = evaluate(f, u);
    if (done) break;
  }
  const ElementType ftype = f.basis->type();
  const int n_corners = ftype == ElementType::Line ? 2 : ftype == ElementType::Triangle ? 3 : 4;
  const Eigen::MatrixXd& corners = f.basis->reference().nodes;
  Hit hit{(q.p - x).squaredNorm(), q, false};
  if (!on_domain_boundary(type, q.u)) return hit;
  auto corner_at = [&](const Eigen::VectorXd& u) {
    for (int c = 0; c < n_corners; ++c)
      if ((u - corners.col(c)).norm() <= 1e-12) return c;
    return -1;
  };
  if (m == 1) {
    const int c = corner_at(q.u);
    hit.rim = c >= 0 && f.rim_corner[static_cast<std::size_t>(c)];
    return hit;
  }
  // The interior iteration stopped on ∂K: the minimum over each edge (and so its corners).
  hit.dist2 = std::numeric_limits<double>::infinity();
  for (int k = 0; k < n_corners; ++k) {
    const FacetPoint e = closest_on_segment(f, x, corners.col(k), corners.col((k + 1) % n_corners));
    if (const double d2 = (e.p - x).squaredNorm(); d2 < hit.dist2) {
      const int c = corner_at(e.u);
      hit = {d2, e, c >= 0 ? f.rim_corner[static_cast<std::size_t>(c)] : f.rim_edge[static_cast<std::size_t>(k)]};
    }
  }
  return hit;
}

// −T G⁻¹ B (G − σB)⁻¹ Tᵀ, symmetrized: the derivative of the unit normal n of the foot point.
Eigen::MatrixXd facet_hessian(const FacetPoint& q, const Eigen::VectorXd& n, double sigma) {
  const int m = static_cast<int>(q.T.cols());
  const Eigen::MatrixXd G = q.T.transpose() * q.T;
  Eigen::MatrixXd B(m, m);
  for (int k = 0; k < m; ++k)
    for (int l = 0; l < m; ++l) B(k, l) = n.dot(q.S.col(k * m + l));
  const Eigen::MatrixXd H = -q.T * G.inverse() * B * (G - sigma * B).inverse() * q.T.transpose();
  return 0.5 * (H + H.transpose());
}

// |projection of −g onto T·K|, K the reference directions du that stay in the facet from u
// (rows a of the active constraints a·du ≥ 0): min ½|T du + g|² over K by its active sets.
double cone_descent(const FacetPoint& q, const Eigen::VectorXd& g) {
  constexpr double tol = 1e-8;  // ε-active: as at the crease within 1e-8 of it (below)
  const int m = static_cast<int>(q.T.cols());
  std::vector<Eigen::VectorXd> rows;
  if (q.type == ElementType::Triangle) {
    if (q.u[0] <= tol) rows.push_back(Eigen::Vector2d(1.0, 0.0));
    if (q.u[1] <= tol) rows.push_back(Eigen::Vector2d(0.0, 1.0));
    if (q.u.sum() >= 1.0 - tol) rows.push_back(Eigen::Vector2d(-1.0, -1.0));
  } else {
    for (int k = 0; k < m; ++k) {
      if (q.u[k] >= 1.0 - tol) rows.push_back(-Eigen::VectorXd::Unit(m, k));
      if (q.u[k] <= -1.0 + tol) rows.push_back(Eigen::VectorXd::Unit(m, k));
    }
  }
  const Eigen::MatrixXd G = q.T.transpose() * q.T;
  const Eigen::VectorXd b = -q.T.transpose() * g;
  auto feasible = [&](const Eigen::VectorXd& du) {
    for (const Eigen::VectorXd& a : rows)
      if (a.dot(du) < -1e-12 * du.norm()) return false;
    return true;
  };
  // The minimiser on {du : a·du = 0} is du = Z (ZᵀGZ)⁻¹ Zᵀb, of objective −½ bᵀdu; du = 0 is always feasible.
  double best_objective = 0.0, descent = 0.0;
  auto offer = [&](const Eigen::MatrixXd& Z) {
    const Eigen::VectorXd du = Z * (Z.transpose() * G * Z).ldlt().solve(Z.transpose() * b);
    if (du.allFinite() && feasible(du) && -0.5 * b.dot(du) < best_objective) {
      best_objective = -0.5 * b.dot(du);
      descent = (q.T * du).norm();
    }
  };
  offer(Eigen::MatrixXd::Identity(m, m));
  if (m == 2)
    for (const Eigen::VectorXd& a : rows) offer(Eigen::Vector2d(-a[1], a[0]));
  return descent;
}

class FacetSurface final : public LevelSetNode {
 public:
  FacetSurface(std::vector<Facet> facets, std::map<std::pair<ElementType, int>, Eigen::MatrixXd> params, double tol)
      : facets_(std::move(facets)), params_(std::move(params)), tol_(tol) {
    std::vector<int> ids(facets_.size());
    std::iota(ids.begin(), ids.end(), 0);
    build(ids, 0, static_cast<int>(ids.size()));
  }

  double value(const Vec& x) const override {
    Vec g;
    return value_gradient(x, g);
  }
  double value_gradient(const Vec& x, Vec& g) const override {
    const Foot f = foot(x);
    g = f.n;
    return f.sigma;
  }
  Eigen::MatrixXd hessian(const Vec& x) const override {
    const Foot f = foot(x);
    Eigen::MatrixXd H = Eigen::MatrixXd::Zero(x.size(), x.size());
    for (const FacetPoint& q : f.through) H += facet_hessian(q, f.n, f.sigma);
    return H / static_cast<double>(f.through.size());
  }
  std::optional<Vec> closest_point(const Vec& x) const override { return foot(x).through.front().p; }
  // A node that Newton drives into a crease from both sides comes within ~1e-10 of it, but its
  // steps across it fail the line search: within 1e-8 (of S's size, and of the reference
  // facet) it counts as on the crease, its cones those of the facets there.
  double stationarity(const Vec& x, const Vec& g) const override {
    const Foot f = foot(x, 1e4 * tol_);
    return f.on_surface ? crease_descent(f, g) : LevelSetNode::stationarity(x, g);
  }
  // Newton steps through a crease that the energy pushes x into from both sides overshoot, and
  // the line search then blocks every other node: such a node keeps to the crease instead.
  Eigen::MatrixXd step_normals(const Vec& x, const Vec& g) const override {
    const Foot f = foot(x, 1e4 * tol_);
    if (!f.on_surface || f.through.size() < 2) return f.n;
    // Orthonormal basis of the facets' normals, nearly parallel ones dropped (Gram–Schmidt).
    Eigen::MatrixXd N(x.size(), 0);
    for (const FacetPoint& q : f.through) {
      Vec n = outward_normal(q.T);
      n -= N * (N.transpose() * n);
      if (n.norm() > 1e-6) {
        N.conservativeResize(Eigen::NoChange, N.cols() + 1);
        N.col(N.cols() - 1) = n.normalized();
      }
      if (N.cols() == x.size()) break;
    }
    const double along = (g - N * (N.transpose() * g)).norm();
    // Otherwise the step enters the facet of steepest descent, in its tangent plane: the mean
    // plane may lead into a neighbour where the energy rises, across the crease.
    double steepest = 0.0;
    const FacetPoint* into = &f.through.front();
    for (const FacetPoint& q : f.through)
      if (const double t = cone_descent(q, g); t > steepest) steepest = t, into = &q;
    return steepest <= along + 1e-12 * g.norm() ? N : Eigen::MatrixXd(outward_normal(into->T));
  }

 private:
  struct Foot {
    double sigma = 0.0;
    bool on_surface = false;
    Vec n;                               // ∇σ
    std::vector<FacetPoint> through;     // the foot point on each facet it belongs to (the nearest first)
  };
  struct Box {
    Eigen::Vector3d lo, hi;
    int first = 0, count = 0, left = -1, right = -1;  // leaf: facets order_[first, first + count)
  };

  int build(std::vector<int>& ids, int begin, int end) {
    Box b{Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()),
          Eigen::Vector3d::Constant(-std::numeric_limits<double>::infinity())};
    for (int i = begin; i < end; ++i) {
      b.lo = b.lo.cwiseMin(facets_[static_cast<std::size_t>(ids[static_cast<std::size_t>(i)])].lo);
      b.hi = b.hi.cwiseMax(facets_[static_cast<std::size_t>(ids[static_cast<std::size_t>(i)])].hi);
    }
    const int me = static_cast<int>(boxes_.size());
    boxes_.push_back(b);
    if (end - begin <= 4) {
      boxes_[static_cast<std::size_t>(me)].first = static_cast<int>(order_.size());
      boxes_[static_cast<std::size_t>(me)].count = end - begin;
      order_.insert(order_.end(), ids.begin() + begin, ids.begin() + end);
      return me;
    }
    Eigen::Index axis = 0;
    (b.hi - b.lo).maxCoeff(&axis);
    const int mid = (begin + end) / 2;
    std::nth_element(ids.begin() + begin, ids.begin() + mid, ids.begin() + end, [&](int i, int j) {
      const Facet &a = facets_[static_cast<std::size_t>(i)], &c = facets_[static_cast<std::size_t>(j)];
      return a.lo[axis] + a.hi[axis] < c.lo[axis] + c.hi[axis];
    });
    const int left = build(ids, begin, mid), right = build(ids, mid, end);
    boxes_[static_cast<std::size_t>(me)].left = left;
    boxes_[static_cast<std::size_t>(me)].right = right;
    return me;
  }

  static double crease_descent(const Foot& f, const Vec& g) {
    double descent = 0.0;  // the steepest of the facets' cones: together they cover S around x
    for (const FacetPoint& q : f.through) descent = std::max(descent, cone_descent(q, g));
    return descent;
  }

  // Distinct for every surface built: the key of the per-thread search cache.
  static std::uint64_t next_serial() {
    static std::atomic<std::uint64_t> next{1};
    return next++;
  }

  template <class B>
  static double box_distance2(const Eigen::Vector3d& x, const B& b) {
    return (x - x.cwiseMax(b.lo).cwiseMin(b.hi)).squaredNorm();
  }

  // Every facet within the crease tolerance 1e4·tol_ of x (the nearest first) and the nearest
  // facet: enough for foot() at either tolerance.
  struct Search {
    std::uint64_t surface = 0;  // serial_ of the surface searched, 0 for none
    Vec x;
    Hit best;
    std::vector<Hit> near;
  };

  // fit_problem asks value, gradient, Hessian, stationarity and step normals at one point in
  // turn: each thread keeps its last search, keyed by the surface's serial (an address may be
  // reused) and x bit for bit, so they cost one search.
  const Search& search(const Vec& x) const {
    thread_local Search last;
    if (last.surface == serial_ && last.x.size() == x.size() && last.x == x) return last;
    last.surface = 0;  // invalid until filled
    last.x = x;
    last.best = Hit{};
    last.near.clear();
    const double near2 = 1e8 * tol_ * tol_;
    Eigen::Vector3d x3 = Eigen::Vector3d::Zero();
    x3.head(x.size()) = x;
    std::vector<int> stack{0};
    while (!stack.empty()) {
      const int top = stack.back();
      stack.pop_back();
      const double bound = std::max(last.best.dist2, near2);
      if (box_distance2(x3, boxes_[static_cast<std::size_t>(top)]) > bound) continue;
      const Box& b = boxes_[static_cast<std::size_t>(top)];
      if (b.left >= 0) {  // the nearer child on top: it tightens the bound sooner
        const bool left_first = box_distance2(x3, boxes_[static_cast<std::size_t>(b.left)]) <=
                                box_distance2(x3, boxes_[static_cast<std::size_t>(b.right)]);
        stack.push_back(left_first ? b.right : b.left);
        stack.push_back(left_first ? b.left : b.right);
        continue;
      }
      for (int i = b.first; i < b.first + b.count; ++i) {
        const Facet& f = facets_[static_cast<std::size_t>(order_[static_cast<std::size_t>(i)])];
        if (box_distance2(x3, f) > std::max(last.best.dist2, near2)) continue;  // as the boxes above
        Hit h = closest_on_facet(f, params_.at({f.basis->type(), f.basis->order()}), x);
        if (h.dist2 <= near2) last.near.push_back(h);
        if (h.dist2 < last.best.dist2) last.best = std::move(h);
      }
    }
    std::stable_sort(last.near.begin(), last.near.end(), [](const Hit& a, const Hit& b) { return a.dist2 < b.dist2; });
    last.surface = serial_;
    return last;
  }

  Foot foot(const Vec& x) const { return foot(x, tol_); }
  // `tol`: the distance within which x counts as on S (at most the search's 1e4·tol_).
  Foot foot(const Vec& x, double tol) const {
    const Search& s = search(x);
    Foot f;
    for (const Hit& h : s.near)
      if (h.dist2 <= tol * tol) f.through.push_back(h.at);
    if (f.through.empty()) {
      const Vec nf = outward_normal(s.best.at.T), r = x - s.best.at.p;
      f.through.push_back(s.best.at);
      if (s.best.rim) {
        f.n = nf;
        f.sigma = r.dot(nf);
      } else {
        f.sigma = std::copysign(std::sqrt(s.best.dist2), r.dot(nf));
        f.n = r / f.sigma;
      }
      return f;
    }
    // On S: the mean normal of the facets through the foot point (the nearest one first).
    f.n = Vec::Zero(x.size());
    for (const FacetPoint& q : f.through) f.n += outward_normal(q.T);
    f.n.normalize();
    f.sigma = (x - f.through.front().p).dot(f.n);
    f.on_surface = true;
    return f;
  }

  std::vector<Facet> facets_;
  std::map<std::pair<ElementType, int>, Eigen::MatrixXd> params_;  // sample parameters, m × s
  double tol_;
  std::uint64_t serial_ = next_serial();
  std::vector<Box> boxes_;
  std::vector<int> order_;
};

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

}  // namespace
}  // namespace detail

LevelSetFunction facet_surface(const Mesh& mesh, const Topology& topology, const std::vector<std::int32_t>& facets) {
  using detail::Facet;
  MESHMORPH_CHECK(!facets.empty(), "facet_surface: no facets");
  const int d = mesh.dim;
  std::vector<Facet> out;
  std::vector<std::vector<std::int32_t>> corner_ids;
  std::map<std::pair<ElementType, int>, Eigen::MatrixXd> params;
  // Uses of each corner edge (3D, by its corner nodes) or corner (2D, (node, node)) within S.
  std::map<std::pair<std::int32_t, std::int32_t>, int> uses;
  auto key = [d](const std::vector<std::int32_t>& ids, int k) {
    const std::int32_t a = ids[static_cast<std::size_t>(k)];
    if (d == 2) return std::pair{a, a};
    const std::int32_t b = ids[(static_cast<std::size_t>(k) + 1) % ids.size()];
    return std::pair{std::min(a, b), std::max(a, b)};
  };
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (std::int32_t id : facets) {
    const std::array<CellFacet, 2>& tf = topology.facets[static_cast<std::size_t>(id)];
    MESHMORPH_CHECK(tf[1].cell < 0, "facet_surface: not a boundary facet");
    const auto [b, c] = topology.locate(tf[0].cell);
    const CellBlock& block = mesh.cells[b];
    const std::vector<std::int32_t> nodes = facet_nodes(block, c, tf[0].local);
    const ElementType type = facet_type(block.type, tf[0].local);
    Facet f;
    f.basis = &lagrange_basis(type, block.order);
    f.nodes = mesh.x(Eigen::all, nodes);
    const Eigen::MatrixXd& u = params.try_emplace({type, block.order}, detail::sample_parameters(type, block.order)).first->second;
    f.samples.resize(d, u.cols());
    for (Eigen::Index s = 0; s < u.cols(); ++s) f.samples.col(s) = f.nodes * f.basis->values(u.col(s));
    Eigen::Vector3d flo = Eigen::Vector3d::Zero(), fhi = Eigen::Vector3d::Zero();
    flo.head(d) = f.samples.rowwise().minCoeff().cwiseMin(f.nodes.rowwise().minCoeff());
    fhi.head(d) = f.samples.rowwise().maxCoeff().cwiseMax(f.nodes.rowwise().maxCoeff());
    // Lagrange maps may bulge past their samples: a margin of 10% of the box.
    const double margin = 0.1 * (fhi - flo).norm();
    f.lo = flo.array() - margin;
    f.hi = fhi.array() + margin;
    lo = lo.cwiseMin(flo);
    hi = hi.cwiseMax(fhi);
    const int n_corners = type == ElementType::Line ? 2 : type == ElementType::Triangle ? 3 : 4;
    std::vector<std::int32_t> ids(nodes.begin(), nodes.begin() + n_corners);
    for (int k = 0; k < n_corners; ++k) ++uses[key(ids, k)];
    out.push_back(std::move(f));
    corner_ids.push_back(std::move(ids));
  }
  std::vector<std::int32_t> rim_nodes;
  for (const auto& [k, n] : uses)
    if (n == 1) rim_nodes.insert(rim_nodes.end(), {k.first, k.second});
  std::sort(rim_nodes.begin(), rim_nodes.end());
  for (std::size_t i = 0; i < out.size(); ++i)
    for (std::size_t k = 0; k < corner_ids[i].size(); ++k) {
      out[i].rim_edge[k] = d == 3 && uses[key(corner_ids[i], static_cast<int>(k))] == 1;
      out[i].rim_corner[k] = std::binary_search(rim_nodes.begin(), rim_nodes.end(), corner_ids[i][k]);
    }
  const double tol = 1e-12 * (hi - lo).norm();
  return LevelSetFunction(std::make_shared<const detail::FacetSurface>(std::move(out), std::move(params), tol), d);
}

}  // namespace meshmorph
