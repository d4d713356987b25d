// SPDX-License-Identifier: MIT
// Closest points on a union of polynomial facets (geometry/detail/polynomial_facet.h): the
// candidates from a bounding-box tree, each pruned by its box and control-point planes against
// the distance to the nearest facet so far.
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

#include "geometry/detail/level_set_node.h"
#include "geometry/detail/polynomial_facet.h"
#include "meshmorph/error.h"
#include "meshmorph/fem/lagrange_basis.h"
#include "meshmorph/fem/trace.h"

namespace meshmorph {

Eigen::VectorXd outward_normal(const Eigen::MatrixXd& T) { return detail::unit_normal(T); }

namespace detail {
namespace {

class FacetSurface final : public LevelSetNode {
 public:
  FacetSurface(std::vector<PolynomialFacet> facets, double tol) : facets_(std::move(facets)), tol_(tol) {
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
    for (const FacetPoint& q : f.through) H += shape_hessian(q, f.n, f.sigma);
    return H / static_cast<double>(f.through.size());
  }
  std::optional<Vec> closest_point(const Vec& x) const override { return Vec(foot(x).through.front().p); }
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
      Vec n = unit_normal(q.T);
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
    return steepest <= along + 1e-12 * g.norm() ? N : Eigen::MatrixXd(unit_normal(into->T));
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
      b.lo = b.lo.cwiseMin(facets_[static_cast<std::size_t>(ids[static_cast<std::size_t>(i)])].lo());
      b.hi = b.hi.cwiseMax(facets_[static_cast<std::size_t>(ids[static_cast<std::size_t>(i)])].hi());
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
      const PolynomialFacet &a = facets_[static_cast<std::size_t>(i)], &c = facets_[static_cast<std::size_t>(j)];
      return a.lo()[axis] + a.hi()[axis] < c.lo()[axis] + c.hi()[axis];
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

  double box_distance2(const Eigen::Vector3d& x, int box) const {
    const Box& b = boxes_[static_cast<std::size_t>(box)];
    return (x - x.cwiseMax(b.lo).cwiseMin(b.hi)).squaredNorm();
  }

  // Every facet within the crease tolerance 1e4·tol_ of x (the nearest first) and the nearest
  // facet: enough for foot() at either tolerance.
  struct Search {
    std::uint64_t surface = 0;  // serial_ of the surface searched, 0 for none
    Vec x;
    FacetHit best;
    std::vector<FacetHit> near;
  };

  // fit_problem asks value, gradient, Hessian, stationarity and step normals at one point in
  // turn: each thread keeps its last search, keyed by the surface's serial (an address may be
  // reused) and x bit for bit, so they cost one search. It never changes a result.
  const Search& search(const Vec& x) const {
    thread_local Search last;
    if (last.surface == serial_ && last.x.size() == x.size() && last.x == x) return last;
    last.surface = 0;  // invalid until filled
    last.x = x;
    last.best = FacetHit{};
    last.near.clear();
    const double near2 = 1e8 * tol_ * tol_;
    Eigen::Vector3d x3 = Eigen::Vector3d::Zero();
    x3.head(x.size()) = x;
    std::array<int, 128> stack{0};  // depth-first: at most one pending sibling per level of the tree
    for (int n_stack = 1; n_stack > 0;) {
      const int top = stack[static_cast<std::size_t>(--n_stack)];
      const double bound = std::max(last.best.dist2, near2);
      if (box_distance2(x3, top) > bound) continue;
      const Box& b = boxes_[static_cast<std::size_t>(top)];
      if (b.left >= 0) {  // the nearer child on top: it tightens the bound sooner
        const bool left_first = box_distance2(x3, b.left) <= box_distance2(x3, b.right);
        stack[static_cast<std::size_t>(n_stack++)] = left_first ? b.right : b.left;
        stack[static_cast<std::size_t>(n_stack++)] = left_first ? b.left : b.right;
        continue;
      }
      for (int i = b.first; i < b.first + b.count; ++i) {
        const PolynomialFacet& f = facets_[static_cast<std::size_t>(order_[static_cast<std::size_t>(i)])];
        if (f.lower_bound2(x3) > std::max(last.best.dist2, near2)) continue;
        FacetHit h = f.closest(x);
        if (h.dist2 <= near2) last.near.push_back(h);
        if (h.dist2 < last.best.dist2) last.best = std::move(h);
      }
    }
    std::stable_sort(last.near.begin(), last.near.end(), [](const FacetHit& a, const FacetHit& b) { return a.dist2 < b.dist2; });
    last.surface = serial_;
    return last;
  }

  Foot foot(const Vec& x) const { return foot(x, tol_); }
  // `tol`: the distance within which x counts as on S (at most the search's 1e4·tol_).
  Foot foot(const Vec& x, double tol) const {
    const Search& s = search(x);
    Foot f;
    for (const FacetHit& h : s.near)
      if (h.dist2 <= tol * tol) f.through.push_back(h.at);
    if (f.through.empty()) {
      const Vec nf = unit_normal(s.best.at.T), r = x - s.best.at.p;
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
    for (const FacetPoint& q : f.through) f.n += unit_normal(q.T);
    f.n.normalize();
    f.sigma = (x - f.through.front().p).dot(f.n);
    f.on_surface = true;
    return f;
  }

  std::vector<PolynomialFacet> facets_;
  double tol_;
  std::uint64_t serial_ = next_serial();
  std::vector<Box> boxes_;
  std::vector<int> order_;
};

}  // namespace
}  // namespace detail

LevelSetFunction facet_surface(const Mesh& mesh, const Topology& topology, const std::vector<std::int32_t>& facets) {
  MESHMORPH_CHECK(!facets.empty(), "facet_surface: no facets");
  const int d = mesh.dim;
  std::vector<std::pair<const LagrangeBasis*, Eigen::MatrixXd>> maps;  // basis, nodes (d × n)
  std::vector<std::vector<std::int32_t>> corner_ids;
  // Uses of each corner edge (3D, by its corner nodes) or corner (2D, (node, node)) within S.
  std::map<std::pair<std::int32_t, std::int32_t>, int> uses;
  auto key = [d](const std::vector<std::int32_t>& ids, int k) {
    const std::int32_t a = ids[static_cast<std::size_t>(k)];
    if (d == 2) return std::pair{a, a};
    const std::int32_t b = ids[(static_cast<std::size_t>(k) + 1) % ids.size()];
    return std::pair{std::min(a, b), std::max(a, b)};
  };
  for (std::int32_t id : facets) {
    const std::array<CellFacet, 2>& tf = topology.facets[static_cast<std::size_t>(id)];
    MESHMORPH_CHECK(tf[1].cell < 0, "facet_surface: not a boundary facet");
    const auto [b, c] = topology.locate(tf[0].cell);
    const CellBlock& block = mesh.cells[b];
    const std::vector<std::int32_t> nodes = facet_nodes(block, c, tf[0].local);
    const ElementType type = facet_type(block.type, tf[0].local);
    maps.emplace_back(&lagrange_basis(type, block.order), mesh.x(Eigen::all, nodes));
    const int n_corners = type == ElementType::Line ? 2 : type == ElementType::Triangle ? 3 : 4;
    std::vector<std::int32_t> ids(nodes.begin(), nodes.begin() + n_corners);
    for (int k = 0; k < n_corners; ++k) ++uses[key(ids, k)];
    corner_ids.push_back(std::move(ids));
  }
  std::vector<std::int32_t> rim_nodes;
  for (const auto& [k, n] : uses)
    if (n == 1) rim_nodes.insert(rim_nodes.end(), {k.first, k.second});
  std::sort(rim_nodes.begin(), rim_nodes.end());
  std::vector<detail::PolynomialFacet> out;
  out.reserve(maps.size());
  Eigen::VectorXd lo = Eigen::VectorXd::Constant(d, std::numeric_limits<double>::infinity()), hi = -lo;
  for (std::size_t i = 0; i < maps.size(); ++i) {
    std::array<bool, 4> rim_edge{}, rim_corner{};
    for (std::size_t k = 0; k < corner_ids[i].size(); ++k) {
      rim_edge[k] = d == 3 && uses[key(corner_ids[i], static_cast<int>(k))] == 1;
      rim_corner[k] = std::binary_search(rim_nodes.begin(), rim_nodes.end(), corner_ids[i][k]);
    }
    const Eigen::MatrixXd& X = maps[i].second;
    out.emplace_back(*maps[i].first, X, rim_edge, rim_corner);
    // S's size: the box of its nodes and Newton start samples.
    lo = lo.cwiseMin(X.rowwise().minCoeff()).cwiseMin(out.back().samples().rowwise().minCoeff());
    hi = hi.cwiseMax(X.rowwise().maxCoeff()).cwiseMax(out.back().samples().rowwise().maxCoeff());
  }
  const double tol = 1e-12 * (hi - lo).norm();
  return LevelSetFunction(std::make_shared<const detail::FacetSurface>(std::move(out), tol), d);
}

}  // namespace meshmorph
