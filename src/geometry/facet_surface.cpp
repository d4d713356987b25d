// SPDX-License-Identifier: MIT
// Closest points on a union of polynomial facets (geometry/detail/polynomial_facet.h): the
// candidates from a box tree, each pruned by its box and control-point planes against the
// distance to the nearest facet so far.
#include "meshmorph/geometry/facet_surface.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <memory>

#include "geometry/detail/box_tree.h"
#include "geometry/detail/level_set_node.h"
#include "geometry/detail/polynomial_facet.h"
#include "meshmorph/error.h"
#include "meshmorph/fem/lagrange_basis.h"
#include "meshmorph/fem/trace.h"
#include "meshmorph/geometry/closest_on_simplex.h"

namespace meshmorph {

Eigen::VectorXd outward_normal(const Eigen::MatrixXd& T) { return detail::unit_normal(T); }

namespace detail {
namespace {

class FacetSurface final : public LevelSetNode {
 public:
  FacetSurface(std::vector<PolynomialFacet> facets, double tol)
      : facets_(std::move(facets)), tol_(tol), tree_(make_tree(facets_)) {}

  double value(const Vec& x) const override { return Answers(*this, x).value(); }
  double value_gradient(const Vec& x, Vec& g) const override {
    const Foot f = Answers(*this, x).foot(tol_);
    g = f.n;
    return f.sigma;
  }
  Eigen::MatrixXd hessian(const Vec& x) const override { return Answers(*this, x).hessian(); }
  std::optional<Vec> closest_point(const Vec& x) const override {
    return Vec(Answers(*this, x).foot(tol_).through.front().p);
  }
  double stationarity(const Vec& x, const Vec& g) const override { return Answers(*this, x).stationarity(g); }
  Eigen::MatrixXd step_normals(const Vec& x, const Vec& g) const override { return Answers(*this, x).step_normals(g); }
  std::unique_ptr<const NodePoint> at(const Vec& x) const override { return std::make_unique<Answers>(*this, x); }

 private:
  struct Foot {
    double sigma = 0.0;
    bool on_surface = false;
    Vec n;                               // ∇σ
    std::vector<FacetPoint> through;     // the foot point on each facet it belongs to (the nearest first)
  };

  // Every facet within the crease tolerance 1e4·tol_ of x (the nearest first) and the nearest
  // facet: enough for a foot at either tolerance.
  struct Search {
    FacetHit best;
    std::vector<FacetHit> near;
  };

  // The answers at one x from one search.
  class Answers final : public NodePoint {
   public:
    Answers(const FacetSurface& s, const Vec& x) : s_(s), x_(x), search_(s.search(x)) {}

    double value() const override { return foot(s_.tol_).sigma; }
    Vec gradient() const override { return foot(s_.tol_).n; }
    Eigen::MatrixXd hessian() const override {
      const Foot f = foot(s_.tol_);
      Eigen::MatrixXd H = Eigen::MatrixXd::Zero(x_.size(), x_.size());
      for (const FacetPoint& q : f.through) H += shape_hessian(q, f.n, f.sigma);
      return H / static_cast<double>(f.through.size());
    }
    // A node that Newton drives into a crease from both sides comes within ~1e-10 of it, but
    // its steps across it fail the line search: within 1e-8 (of S's size, and of the
    // reference facet) it counts as on the crease, its cones those of the facets there.
    double stationarity(const Vec& g) const override {
      const Foot f = foot(1e4 * s_.tol_);
      if (f.on_surface) return crease_descent(f, g);
      const Vec n = gradient().normalized();  // the smooth case's |g − (g·n)n|
      return (g - n * n.dot(g)).norm();
    }
    // Newton steps through a crease that the energy pushes x into from both sides overshoot,
    // and the line search then blocks every other node: such a node keeps to the crease.
    Eigen::MatrixXd step_normals(const Vec& g) const override {
      const Foot f = foot(1e4 * s_.tol_);
      if (!f.on_surface || f.through.size() < 2) return f.n;
      // Orthonormal basis of the facets' normals, nearly parallel ones dropped (Gram–Schmidt).
      Eigen::MatrixXd N(x_.size(), 0);
      for (const FacetPoint& q : f.through) {
        Vec n = unit_normal(q.T);
        n -= N * (N.transpose() * n);
        if (n.norm() > 1e-6) {
          N.conservativeResize(Eigen::NoChange, N.cols() + 1);
          N.col(N.cols() - 1) = n.normalized();
        }
        if (N.cols() == x_.size()) break;
      }
      const double along = (g - N * (N.transpose() * g)).norm();
      // Otherwise the step enters the facet of steepest descent, in its tangent plane: the
      // mean plane may lead into a neighbour where the energy rises, across the crease.
      double steepest = 0.0;
      const FacetPoint* into = &f.through.front();
      for (const FacetPoint& q : f.through)
        if (const double t = cone_descent(q, g); t > steepest) steepest = t, into = &q;
      return steepest <= along + 1e-12 * g.norm() ? N : Eigen::MatrixXd(unit_normal(into->T));
    }

    // `tol`: the distance within which x counts as on S (at most the search's 1e4·tol_).
    Foot foot(double tol) const {
      Foot f;
      for (const FacetHit& h : search_.near)
        if (h.dist2 <= tol * tol) f.through.push_back(h.at);
      if (f.through.empty()) {
        const FacetHit& best = search_.best;
        const Vec nf = unit_normal(best.at.T), r = x_ - best.at.p;
        f.through.push_back(best.at);
        if (best.rim) {
          f.n = nf;
          f.sigma = r.dot(nf);
        } else {
          f.sigma = std::copysign(std::sqrt(best.dist2), r.dot(nf));
          f.n = r / f.sigma;
        }
        return f;
      }
      // On S: the mean normal of the facets through the foot point (the nearest one first).
      f.n = Vec::Zero(x_.size());
      for (const FacetPoint& q : f.through) f.n += unit_normal(q.T);
      f.n.normalize();
      f.sigma = (x_ - f.through.front().p).dot(f.n);
      f.on_surface = true;
      return f;
    }

   private:
    const FacetSurface& s_;
    Vec x_;
    Search search_;
  };

  // Facets split at the centres of their control points' boxes.
  static BoxTree make_tree(const std::vector<PolynomialFacet>& facets) {
    const auto n = static_cast<Eigen::Index>(facets.size());
    Eigen::Matrix3Xd lo(3, n), hi(3, n);
    for (Eigen::Index i = 0; i < n; ++i) {
      lo.col(i) = facets[static_cast<std::size_t>(i)].lo();
      hi.col(i) = facets[static_cast<std::size_t>(i)].hi();
    }
    return BoxTree(lo, hi, lo + hi);
  }

  static double crease_descent(const Foot& f, const Vec& g) {
    double descent = 0.0;  // the steepest of the facets' cones: together they cover S around x
    for (const FacetPoint& q : f.through) descent = std::max(descent, cone_descent(q, g));
    return descent;
  }

  Search search(const Vec& x) const {
    Search s;
    const double near2 = 1e8 * tol_ * tol_;
    const Eigen::Vector3d x3 = padded_3d(x);
    const auto bound = [&] { return std::max(s.best.dist2, near2); };
    tree_.nearest_first(
        x3, [&](double box2) { return box2 <= bound(); },
        [&](int i) {
          const PolynomialFacet& f = facets_[static_cast<std::size_t>(i)];
          if (f.lower_bound2(x3) > bound()) return;
          FacetHit h = f.closest(x);
          if (h.dist2 <= near2) s.near.push_back(h);
          if (h.dist2 < s.best.dist2) s.best = std::move(h);
        });
    std::stable_sort(s.near.begin(), s.near.end(), [](const FacetHit& a, const FacetHit& b) { return a.dist2 < b.dist2; });
    return s;
  }

  std::vector<PolynomialFacet> facets_;
  double tol_;
  BoxTree tree_;
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
