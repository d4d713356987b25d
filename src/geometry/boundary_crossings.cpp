// SPDX-License-Identifier: MIT
#include "meshmorph/geometry/boundary_crossings.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include "geometry/detail/box_tree.h"
#include "meshmorph/fem/reference_element.h"
#include "meshmorph/fem/trace.h"

namespace meshmorph {
namespace {

// A straight piece of the boundary: a segment (third node −1) or a triangle, by node.
struct Piece {
  std::array<std::int32_t, 3> nodes{-1, -1, -1};
  std::int32_t facet = -1;
};

// The pieces of a facet of (type, order) as facet-local node indices: the polygon through
// its nodes (a segment per gap along a line, two triangles per cell of a quadrilateral's
// node lattice, one or two per cell of a triangle's).
std::vector<std::array<int, 3>> local_pieces(ElementType type, int order) {
  const Eigen::MatrixXd& ref = reference_element(type, order).nodes;
  std::vector<std::array<int, 3>> out;
  if (type == ElementType::Line) {
    std::vector<int> along(static_cast<std::size_t>(ref.cols()));
    for (std::size_t i = 0; i < along.size(); ++i) along[i] = static_cast<int>(i);
    std::sort(along.begin(), along.end(), [&](int a, int b) { return ref(0, a) < ref(0, b); });
    for (std::size_t i = 0; i + 1 < along.size(); ++i) out.push_back({along[i], along[i + 1], -1});
    return out;
  }
  // Node of each lattice point (i, j), i, j = 0 … order.
  const bool simplex = type == ElementType::Triangle;
  std::map<std::pair<long, long>, int> at;
  for (Eigen::Index k = 0; k < ref.cols(); ++k) {
    const double u = simplex ? ref(0, k) : 0.5 * (ref(0, k) + 1.0), v = simplex ? ref(1, k) : 0.5 * (ref(1, k) + 1.0);
    at[{std::lround(u * order), std::lround(v * order)}] = static_cast<int>(k);
  }
  for (long i = 0; i < order; ++i)
    for (long j = 0; j < order; ++j) {
      if (simplex && i + j >= order) continue;
      const int a = at.at({i, j}), b = at.at({i + 1, j}), d = at.at({i, j + 1});
      out.push_back({a, b, d});
      if (!simplex || i + j + 1 < order) {
        const int c = at.at({i + 1, j + 1});
        out.push_back({b, c, d});
      }
    }
  return out;
}

double orient2d(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  return (b(0) - a(0)) * (c(1) - a(1)) - (b(1) - a(1)) * (c(0) - a(0));
}

double orient3d(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c, const Eigen::Vector3d& d) {
  return (b - a).cross(c - a).dot(d - a);
}

// Pieces that lie on one line or in one plane up to `tol` (a flat facet's pieces, whose
// elevated nodes sit off it by rounding, and its flat neighbours') do not cross.
bool segments_cross(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c, const Eigen::Vector3d& d,
                    double tol) {
  const double oc = orient2d(a, b, c), od = orient2d(a, b, d);
  if (std::abs(oc) <= tol && std::abs(od) <= tol) return false;
  return oc * od < 0.0 && orient2d(c, d, a) * orient2d(c, d, b) < 0.0;
}

// Segment pq through the inside of triangle abc, from one side to the other.
bool pierces(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
             const Eigen::Vector3d& c) {
  if (!(orient3d(a, b, c, p) * orient3d(a, b, c, q) < 0.0)) return false;
  const double s1 = orient3d(p, q, a, b), s2 = orient3d(p, q, b, c), s3 = orient3d(p, q, c, a);
  return (s1 > 0.0 && s2 > 0.0 && s3 > 0.0) || (s1 < 0.0 && s2 < 0.0 && s3 < 0.0);
}

// Two triangles in general position that cross meet along a segment whose ends are where an
// edge of one pierces the other.
bool triangles_cross(const std::array<Eigen::Vector3d, 3>& s, const std::array<Eigen::Vector3d, 3>& t, double tol) {
  double off = 0.0;
  for (const auto& x : t) off = std::max(off, std::abs(orient3d(s[0], s[1], s[2], x)));
  if (off <= tol) return false;
  for (int e = 0; e < 3; ++e) {
    if (pierces(s[e], s[(e + 1) % 3], t[0], t[1], t[2])) return true;
    if (pierces(t[e], t[(e + 1) % 3], s[0], s[1], s[2])) return true;
  }
  return false;
}

}  // namespace

BoundaryCrossings boundary_crossings(const Mesh& mesh, const Topology& topology) {
  BoundaryCrossings out;
  std::vector<Piece> pieces;
  std::map<std::pair<ElementType, int>, std::vector<std::array<int, 3>>> tables;
  for (auto f : topology.boundary_facets) {
    const CellFacet& cf = topology.facets[static_cast<std::size_t>(f)][0];
    const auto [b, c] = topology.locate(cf.cell);
    const CellBlock& block = mesh.cells[b];
    const ElementType type = facet_type(block.type, cf.local);
    auto& table = tables[{type, block.order}];
    if (table.empty()) table = local_pieces(type, block.order);
    const std::vector<std::int32_t> nodes = facet_nodes(block, c, cf.local);
    for (const auto& local : table) {
      Piece p;
      p.facet = f;
      for (int k = 0; k < 3; ++k) p.nodes[static_cast<std::size_t>(k)] = local[static_cast<std::size_t>(k)] < 0 ? -1 : nodes[static_cast<std::size_t>(local[static_cast<std::size_t>(k)])];
      pieces.push_back(p);
    }
  }
  if (pieces.size() < 2) return out;

  const auto n = static_cast<Eigen::Index>(pieces.size());
  const int corners = mesh.dim == 2 ? 2 : 3;
  auto point = [&](std::int32_t node) {
    Eigen::Vector3d x = Eigen::Vector3d::Zero();
    x.head(mesh.dim) = mesh.x.col(node);
    return x;
  };
  Eigen::Matrix3Xd lo(3, n), hi(3, n);
  for (Eigen::Index i = 0; i < n; ++i) {
    lo.col(i) = hi.col(i) = point(pieces[static_cast<std::size_t>(i)].nodes[0]);
    for (int k = 1; k < corners; ++k) {
      const Eigen::Vector3d x = point(pieces[static_cast<std::size_t>(i)].nodes[static_cast<std::size_t>(k)]);
      lo.col(i) = lo.col(i).cwiseMin(x);
      hi.col(i) = hi.col(i).cwiseMax(x);
    }
  }
  if (!lo.allFinite() || !hi.allFinite()) return out;  // non-finite nodes: invalid cells already
  const detail::BoxTree tree(lo, hi, lo + hi);
  auto shares_node = [&](const Piece& p, const Piece& q) {
    for (int k = 0; k < corners; ++k)
      for (int l = 0; l < corners; ++l)
        if (p.nodes[static_cast<std::size_t>(k)] == q.nodes[static_cast<std::size_t>(l)]) return true;
    return false;
  };
  for (Eigen::Index i = 0; i < n; ++i) {
    const Piece& p = pieces[static_cast<std::size_t>(i)];
    tree.overlapping(lo.col(i), hi.col(i), [&](int j) {
      if (j <= i || (lo.col(j).array() > hi.col(i).array()).any() || (hi.col(j).array() < lo.col(i).array()).any()) return;
      const Piece& q = pieces[static_cast<std::size_t>(j)];
      // Pieces of one facet cross only where the facet folds, which inverts its cell.
      if (p.facet == q.facet || shares_node(p, q)) return;
      // Orientations are areas (2D) or volumes (3D) on the pair's scale L: below 1e-12 L^d
      // they are rounding.
      const double L = (hi.col(i).cwiseMax(hi.col(j)) - lo.col(i).cwiseMin(lo.col(j))).norm();
      const double tol = 1e-12 * std::pow(L, mesh.dim);
      const bool cross =
          mesh.dim == 2 ? segments_cross(point(p.nodes[0]), point(p.nodes[1]), point(q.nodes[0]), point(q.nodes[1]), tol)
                        : triangles_cross({point(p.nodes[0]), point(p.nodes[1]), point(p.nodes[2])},
                                          {point(q.nodes[0]), point(q.nodes[1]), point(q.nodes[2])}, tol);
      if (!cross) return;
      if (out.count++ == 0 || std::make_pair(std::min(p.facet, q.facet), std::max(p.facet, q.facet)) <
                                  std::make_pair(out.first[0], out.first[1]))
        out.first = {std::min(p.facet, q.facet), std::max(p.facet, q.facet)};
    });
  }
  return out;
}

}  // namespace meshmorph
