// SPDX-License-Identifier: MIT
// Sharp features of a CSG surface (docs/fit.md, "Sharp features"): the surface of a sharp CSG
// is the union of its pieces' zero sets, so a node on an edge satisfies two of them and a
// node on a corner three (two in 2D). The fitted facets are labelled with their piece, and
// the nodes where facets of different pieces meet are the feature nodes.
#include "meshmorph/methods/fit_features.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <utility>

#include <Eigen/Dense>

namespace meshmorph {
namespace {

bool blended(const LevelSet& ls) {
  return std::visit([](const auto& s) {
    if constexpr (requires { s.blend; }) return s.blend > 0.0;
    return false;
  }, ls.shape);
}

void collect_pieces(const LevelSet& ls, int dim, std::vector<LevelSet>& out) {
  if (const auto* d = std::get_if<DistanceLevelSet>(&ls.shape)) return collect_pieces(d->operands.front(), dim, out);
  if (const auto* b = std::get_if<BoxLevelSet>(&ls.shape)) {
    for (int k = 0; k < dim; ++k)
      for (const double side : {-1.0, 1.0}) {
        PlaneLevelSet p{b->center, CaseVector::Zero(dim)};
        p.point[k] += 0.5 * side * b->size[k];
        p.normal[k] = side;
        out.push_back({p, ls.key_path});
      }
    return;
  }
  if (!blended(ls)) {
    bool csg = false;
    std::visit([&](const auto& s) {
      if constexpr (requires { s.blend; }) {
        csg = true;
        for (const LevelSet& o : s.operands) collect_pieces(o, dim, out);
      }
    }, ls.shape);
    if (csg) return;
  }
  out.push_back(ls);
}

// Facet element layout: the number of corners and of nodes on each edge, from its node count
// at the mesh's order (a line in 2D, a quadrilateral or a triangle in 3D).
std::pair<int, int> facet_layout(std::size_t n, int dim, int order) {
  if (dim == 2) return {2, order - 1};
  return {n == static_cast<std::size_t>((order + 1) * (order + 1)) ? 4 : 3, order - 1};
}

}  // namespace

std::vector<LevelSet> smooth_pieces(const LevelSet& ls, int dim) {
  std::vector<LevelSet> out;
  collect_pieces(ls, dim, out);
  return out;
}

const LevelSet& exact_level_set(const LevelSet& ls) {
  if (const auto* d = std::get_if<DistanceLevelSet>(&ls.shape)) return exact_level_set(d->operands.front());
  return ls;
}

std::optional<Eigen::VectorXd> project_to_feature(const Eigen::VectorXd& x, const std::vector<const LevelSetFunction*>& pieces) {
  const auto m = static_cast<Eigen::Index>(pieces.size());
  Eigen::VectorXd p = x, r(m);
  Eigen::MatrixXd J(m, x.size());
  const double scale = std::max(1.0, x.norm());
  for (int it = 0; it < 50; ++it) {
    for (Eigen::Index i = 0; i < m; ++i) {
      r[i] = pieces[static_cast<std::size_t>(i)]->value(p);
      J.row(i) = pieces[static_cast<std::size_t>(i)]->gradient(p).transpose();
    }
    if (!r.allFinite() || !J.allFinite()) break;
    if (r.norm() <= 1e-13 * scale) return p;
    // The least-norm step onto the linearised constraints.
    Eigen::LDLT<Eigen::MatrixXd> ldlt(J * J.transpose());
    if (ldlt.info() != Eigen::Success || ldlt.rcond() < 1e-12) break;
    p -= J.transpose() * ldlt.solve(r);
  }
  return std::nullopt;
}

double distance_to_feature(const Eigen::VectorXd& x, const std::vector<const LevelSetFunction*>& pieces) {
  const std::optional<Eigen::VectorXd> p = project_to_feature(x, pieces);
  return p ? (*p - x).norm() : std::numeric_limits<double>::infinity();
}

FitFeatures find_features(const Mesh& mesh, const std::vector<std::vector<std::int32_t>>& facets,
                          const LevelSetFunction& surface, const std::vector<LevelSetFunction>& pieces, double reach) {
  FitFeatures result;
  const int dim = mesh.dim, order = mesh.order();
  if (pieces.size() < 2 || facets.empty()) return result;

  // The piece of each facet: active at the closest point of the surface to its centroid,
  // the nearest one where several are (the closest point on an edge).
  std::vector<int> label(facets.size(), -1);
  for (std::size_t f = 0; f < facets.size(); ++f) {
    const int corners = facet_layout(facets[f].size(), dim, order).first;
    Eigen::VectorXd c = Eigen::VectorXd::Zero(dim);
    for (int k = 0; k < corners; ++k) c += mesh.x.col(facets[f][static_cast<std::size_t>(k)]);
    c /= corners;
    const std::optional<Eigen::VectorXd> p = surface.closest_point(c);
    const double tol = 1e-8 * std::max(1.0, c.norm());
    double best = std::numeric_limits<double>::infinity(), best_any = best;
    int any = 0;
    for (std::size_t i = 0; i < pieces.size(); ++i) {
      const double near = std::abs(pieces[i].value(c));
      if (near < best_any) best_any = near, any = static_cast<int>(i);
      if (p && std::abs(pieces[i].value(*p)) <= tol && near < best) best = near, label[f] = static_cast<int>(i);
    }
    if (label[f] < 0) label[f] = any;
  }

  // Pieces met at each node: on a mesh edge (3D) or vertex (2D) between facets of two pieces.
  std::map<std::int32_t, std::vector<int>> met;
  std::set<std::int32_t> turns;  // feature vertices that a facet turns round (3D)
  const auto meet = [&](std::int32_t node, int a, int b) {
    std::vector<int>& m = met[node];
    for (int l : {a, b})
      if (std::find(m.begin(), m.end(), l) == m.end()) m.push_back(l);
  };
  if (dim == 2) {
    std::map<std::int32_t, std::vector<int>> at_vertex;
    for (std::size_t f = 0; f < facets.size(); ++f)
      for (int k = 0; k < 2; ++k) at_vertex[facets[f][static_cast<std::size_t>(k)]].push_back(label[f]);
    for (const auto& [node, labels] : at_vertex)
      if (labels.size() == 2 && labels[0] != labels[1]) meet(node, labels[0], labels[1]);
  } else {
    struct Edge {
      std::vector<std::int32_t> nodes;  // its two corners, then its inner nodes
      std::vector<int> labels;          // of its facets
      bool feature() const { return labels.size() == 2 && labels[0] != labels[1]; }
      std::pair<int, int> pair() const { return {std::min(labels[0], labels[1]), std::max(labels[0], labels[1])}; }
    };
    std::map<std::pair<std::int32_t, std::int32_t>, Edge> edges;
    const auto key = [&](std::size_t f, int k, int corners) {
      const std::int32_t a = facets[f][static_cast<std::size_t>(k % corners)], b = facets[f][static_cast<std::size_t>((k + 1) % corners)];
      return std::pair{std::min(a, b), std::max(a, b)};
    };
    for (std::size_t f = 0; f < facets.size(); ++f) {
      const auto [corners, inner] = facet_layout(facets[f].size(), dim, order);
      for (int k = 0; k < corners; ++k) {
        Edge& e = edges[key(f, k, corners)];
        if (e.nodes.empty()) {
          e.nodes = {facets[f][static_cast<std::size_t>(k)], facets[f][static_cast<std::size_t>((k + 1) % corners)]};
          for (int j = 0; j < inner; ++j) e.nodes.push_back(facets[f][static_cast<std::size_t>(corners + k * inner + j)]);
        }
        e.labels.push_back(label[f]);
      }
    }
    // A facet whose two edges at a vertex lie on one feature (a staircase turns there) would
    // be flat at that vertex once both do: the feature cuts across the facet instead, and the
    // vertex and the inner nodes of both edges stay surface nodes (unplaced).
    for (std::size_t f = 0; f < facets.size(); ++f) {
      const int corners = facet_layout(facets[f].size(), dim, order).first;
      for (int k = 0; k < corners; ++k) {
        const Edge& in = edges[key(f, k + corners - 1, corners)];
        const Edge& out = edges[key(f, k, corners)];
        if (in.feature() && out.feature() && in.pair() == out.pair()) turns.insert(facets[f][static_cast<std::size_t>(k)]);
      }
    }
    for (const auto& [ends, e] : edges)
      if (e.feature())
        for (std::int32_t node : e.nodes) meet(node, e.labels[0], e.labels[1]);
    // A corner (three pieces) is not a turn; an edge's inner nodes go with its ends.
    std::erase_if(turns, [&](std::int32_t v) { return met[v].size() > 2; });
    for (const auto& [ends, e] : edges)
      if (e.feature() && (turns.contains(e.nodes[0]) || turns.contains(e.nodes[1])))
        for (std::size_t j = 2; j < e.nodes.size(); ++j) turns.insert(e.nodes[j]);
  }

  for (auto& [node, labels] : met) {
    const Eigen::VectorXd x = mesh.x.col(node);
    // More pieces than the dimension cannot all hold: the d nearest.
    std::sort(labels.begin(), labels.end(), [&](int a, int b) {
      return std::abs(pieces[static_cast<std::size_t>(a)].value(x)) < std::abs(pieces[static_cast<std::size_t>(b)].value(x));
    });
    if (labels.size() > static_cast<std::size_t>(dim)) labels.resize(static_cast<std::size_t>(dim));
    std::vector<const LevelSetFunction*> active;
    for (int l : labels) active.push_back(&pieces[static_cast<std::size_t>(l)]);
    // The pieces meet near the node, on the surface (not where another piece cuts it away).
    const std::optional<Eigen::VectorXd> target = project_to_feature(x, active);
    if (!target || !((*target - x).norm() <= reach) || std::abs(surface.value(*target)) > 1e-9 * reach) continue;
    std::sort(labels.begin(), labels.end());
    if (turns.contains(node)) {
      result.unplaced.push_back(node);
      result.unplaced_pieces.push_back(labels);
      continue;
    }
    result.nodes.push_back(node);
    result.pieces.push_back(labels);
    ++(labels.size() == static_cast<std::size_t>(dim) ? result.on_corners : result.on_edges);
  }
  return result;
}

double max_feature_distance(const std::vector<std::int32_t>& nodes, const std::vector<std::vector<int>>& node_pieces,
                            const std::vector<LevelSetFunction>& pieces, const Eigen::MatrixXd& x) {
  double e = 0.0;
  for (std::size_t k = 0; k < nodes.size(); ++k) {
    std::vector<const LevelSetFunction*> active;
    for (int l : node_pieces[k]) active.push_back(&pieces[static_cast<std::size_t>(l)]);
    e = std::max(e, distance_to_feature(x.col(nodes[k]), active));
  }
  return e;
}

}  // namespace meshmorph
