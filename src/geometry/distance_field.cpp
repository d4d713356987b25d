// SPDX-License-Identifier: MIT
// The distance field of distance_field.h: refinement of a root grid where the indicator
// changes sign, marching simplices on the finest cells, exact point–facet distances through
// a box tree. Points of the surface and of the tree are padded to 3D (z = 0 in 2D).
#include "meshmorph/geometry/distance_field.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "geometry/detail/box_tree.h"
#include "meshmorph/fem/reference_element.h"
#include "meshmorph/geometry/closest_on_simplex.h"

namespace meshmorph {
namespace {

using Vec = Eigen::VectorXd;
using P3 = Eigen::Vector3d;

constexpr int kLattice = 8;  // lattice intervals along each side of a grown cell

struct Cell {
  int level = 0;
  std::array<std::int64_t, 3> ijk{0, 0, 0};
};

// Integer node lattice: the corners and Lagrange nodes of every cell, at spacing
// h0 / (2^levels · order).
struct Lattice {
  int dim = 0, levels = 0, order = 1;
  Vec lower;
  double h0 = 0;
  std::array<std::int64_t, 3> extent{1, 1, 1};  // lattice points per axis

  std::int64_t scale(int level) const { return (std::int64_t{1} << (levels - level)) * order; }
  double spacing() const { return std::ldexp(h0, -levels) / order; }
  double size(int level) const { return std::ldexp(h0, -level); }
  std::int64_t key(const std::array<std::int64_t, 3>& I) const { return I[0] + extent[0] * (I[1] + extent[1] * I[2]); }
  Vec point(const std::array<std::int64_t, 3>& I) const {
    Vec x(dim);
    for (int k = 0; k < dim; ++k) x[k] = lower[k] + static_cast<double>(I[k]) * spacing();
    return x;
  }
  // Lattice index of corner `bits` (bit k: the far side along axis k) of a cell.
  std::array<std::int64_t, 3> corner(const Cell& c, int bits) const {
    std::array<std::int64_t, 3> I{0, 0, 0};
    for (int k = 0; k < dim; ++k) I[k] = (c.ijk[k] + ((bits >> k) & 1)) * scale(c.level);
    return I;
  }
};

bool changes_sign(const std::function<bool(const Vec&)>& inside, const Lattice& L, const Cell& c) {
  const double s = L.size(c.level), step = 2.0 * s / kLattice;
  Vec origin(L.dim), x(L.dim);
  for (int k = 0; k < L.dim; ++k) origin[k] = L.lower[k] + (static_cast<double>(c.ijk[k]) - 0.5) * s;
  const int n = kLattice + 1, total = L.dim == 2 ? n * n : n * n * n;
  bool first = false;
  for (int p = 0; p < total; ++p) {
    for (int k = 0, q = p; k < L.dim; ++k, q /= n) x[k] = origin[k] + (q % n) * step;
    const bool in = inside(x);
    if (p == 0) first = in;
    else if (in != first) return true;
  }
  return false;
}

// The distance to the nearest of the facets (segments: 2 corners, triangles: 3), by a box
// tree over their corners' boxes split at their centroids.
class FacetDistance {
 public:
  FacetDistance(std::vector<std::array<P3, 3>> facets, int corners)
      : facets_(std::move(facets)), corners_(corners), tree_(make_tree(facets_, corners_)) {}

  double distance(const P3& p) const {
    double best = std::numeric_limits<double>::infinity();
    tree_.nearest_first(
        p, [&](double box2) { return box2 < best; },
        [&](int f) {
          const auto& v = facets_[static_cast<std::size_t>(f)];
          const P3 q = corners_ == 2 ? closest_on_segment(p, v[0], v[1]) : closest_on_triangle(p, v[0], v[1], v[2]);
          best = std::min(best, (q - p).squaredNorm());
        });
    return std::sqrt(best);
  }

 private:
  static detail::BoxTree make_tree(const std::vector<std::array<P3, 3>>& facets, int corners) {
    const auto n = static_cast<Eigen::Index>(facets.size());
    Eigen::Matrix3Xd lo(3, n), hi(3, n), centroid(3, n);
    for (Eigen::Index f = 0; f < n; ++f) {
      const auto& v = facets[static_cast<std::size_t>(f)];
      lo.col(f) = hi.col(f) = v[0];
      for (std::size_t k = 1; k < static_cast<std::size_t>(corners); ++k) {
        lo.col(f) = lo.col(f).cwiseMin(v[k]);
        hi.col(f) = hi.col(f).cwiseMax(v[k]);
      }
      centroid.col(f) = corners == 2 ? P3((v[0] + v[1]) / 2) : P3((v[0] + v[1] + v[2]) / 3);
    }
    return detail::BoxTree(lo, hi, centroid);
  }

  std::vector<std::array<P3, 3>> facets_;
  int corners_;
  detail::BoxTree tree_;
};

}  // namespace

DistanceField distance_field(const std::function<bool(const Vec&)>& inside, int dim, const DistanceFieldOptions& o) {
  if (dim != 2 && dim != 3) throw std::invalid_argument("distance_field: dimension must be 2 or 3");
  if (o.lower.size() != dim || o.upper.size() != dim || !o.lower.allFinite() || !o.upper.allFinite() ||
      !((o.upper - o.lower).minCoeff() > 0))
    throw std::invalid_argument("distance_field: the box must have " + std::to_string(dim) +
                                " finite coordinates per corner and upper > lower");
  if (o.cells < 1) throw std::invalid_argument("distance_field: cells must be at least 1");
  if (o.levels < 0 || o.levels > 12) throw std::invalid_argument("distance_field: levels must be 0 to 12");
  if (o.order < 1 || o.order > 3) throw std::invalid_argument("distance_field: order must be 1 to 3");

  Lattice L;
  L.dim = dim;
  L.levels = o.levels;
  L.order = o.order;
  L.lower = o.lower;
  L.h0 = (o.upper - o.lower).maxCoeff() / o.cells;
  std::array<std::int64_t, 3> roots{1, 1, 1};
  for (int k = 0; k < dim; ++k) {
    roots[static_cast<std::size_t>(k)] = std::max<std::int64_t>(1, static_cast<std::int64_t>(std::ceil((o.upper[k] - o.lower[k]) / L.h0 - 1e-9)));
    L.extent[static_cast<std::size_t>(k)] = roots[static_cast<std::size_t>(k)] * L.scale(0) + 1;
  }

  // Refinement: the cells of each level that see a sign change are split into 2^d children.
  std::vector<Cell> cells, active;
  for (std::int64_t k = 0; k < roots[2]; ++k)
    for (std::int64_t j = 0; j < roots[1]; ++j)
      for (std::int64_t i = 0; i < roots[0]; ++i) active.push_back({0, {i, j, k}});
  const int children = 1 << dim;
  for (int level = 0; level < o.levels; ++level) {
    std::vector<std::uint8_t> split(active.size());
#pragma omp parallel for schedule(dynamic, 16)
    for (std::size_t c = 0; c < active.size(); ++c) split[c] = changes_sign(inside, L, active[c]) ? 1 : 0;
    std::vector<Cell> next;
    for (std::size_t c = 0; c < active.size(); ++c) {
      if (!split[c]) {
        cells.push_back(active[c]);
        continue;
      }
      for (int b = 0; b < children; ++b) {
        Cell child{level + 1, {0, 0, 0}};
        for (int k = 0; k < 3; ++k) child.ijk[static_cast<std::size_t>(k)] = 2 * active[c].ijk[static_cast<std::size_t>(k)] + ((b >> k) & 1);
        next.push_back(child);
      }
    }
    active = std::move(next);
  }
  const std::size_t first_finest = cells.size();
  cells.insert(cells.end(), active.begin(), active.end());

  DistanceField out;
  out.finest_size = L.size(o.levels);

  // Zero set: marching Kuhn simplices of the finest cells. A simplex of the cube is the
  // path 0 → e_π0 → e_π0 + e_π1 (→ 1,1,1) through its corners for a permutation π.
  std::vector<std::array<int, 4>> simplices;
  {
    std::array<int, 3> perm{0, 1, 2};
    do {
      std::array<int, 4> s{0, 0, 0, 0};
      for (int m = 0; m < dim; ++m) s[static_cast<std::size_t>(m + 1)] = s[static_cast<std::size_t>(m)] | (1 << perm[static_cast<std::size_t>(m)]);
      simplices.push_back(s);
    } while (std::next_permutation(perm.begin(), perm.begin() + dim));
  }
  // Crossing edges (inside corner key, outside corner key) → index, found serially; the
  // bisections run in parallel.
  struct Edge { std::array<std::int64_t, 3> in, out; };
  struct PairHash {
    std::size_t operator()(const std::pair<std::int64_t, std::int64_t>& p) const {
      return std::hash<std::int64_t>()(p.first * 1000003 ^ p.second);
    }
  };
  std::unordered_map<std::pair<std::int64_t, std::int64_t>, int, PairHash> edge_index;
  std::vector<Edge> edges;
  std::vector<std::array<int, 4>> marched;  // per simplex with a crossing: edge indices, −1 unused
  const auto edge_of = [&](const std::array<std::int64_t, 3>& a, const std::array<std::int64_t, 3>& b) {
    const auto [it, fresh] = edge_index.try_emplace({L.key(a), L.key(b)}, static_cast<int>(edges.size()));
    if (fresh) edges.push_back({a, b});
    return it->second;
  };
  for (std::size_t c = first_finest; c < cells.size(); ++c) {
    std::array<std::array<std::int64_t, 3>, 8> corner{};
    std::array<bool, 8> in{};
    int n_in = 0;
    for (int b = 0; b < children; ++b) {
      corner[static_cast<std::size_t>(b)] = L.corner(cells[c], b);
      in[static_cast<std::size_t>(b)] = inside(L.point(corner[static_cast<std::size_t>(b)]));
      n_in += in[static_cast<std::size_t>(b)];
    }
    if (n_in == 0 || n_in == children) continue;
    for (const auto& s : simplices) {
      std::array<int, 4> v{};
      int k_in = 0;
      for (int m = 0; m <= dim; ++m) k_in += in[static_cast<std::size_t>(s[static_cast<std::size_t>(m)])];
      if (k_in == 0 || k_in == dim + 1) continue;
      // Order the simplex's corners inside first.
      int a = 0, z = dim;
      for (int m = 0; m <= dim; ++m) {
        const int corner_id = s[static_cast<std::size_t>(m)];
        if (in[static_cast<std::size_t>(corner_id)]) v[static_cast<std::size_t>(a++)] = corner_id;
        else v[static_cast<std::size_t>(z--)] = corner_id;
      }
      const auto e = [&](int i, int o_) { return edge_of(corner[static_cast<std::size_t>(v[static_cast<std::size_t>(i)])], corner[static_cast<std::size_t>(v[static_cast<std::size_t>(o_)])]); };
      if (dim == 2) {
        // One corner apart from the other two: the segment between its two edges.
        if (k_in == 1) marched.push_back({e(0, 1), e(0, 2), -1, -1});
        else marched.push_back({e(0, 2), e(1, 2), -1, -1});
      } else if (k_in == 1) {
        marched.push_back({e(0, 1), e(0, 2), e(0, 3), -1});
      } else if (k_in == 3) {
        marched.push_back({e(0, 3), e(1, 3), e(2, 3), -1});
      } else {  // inside {0, 1}, outside {2, 3}: the quadrilateral 02, 03, 13, 12
        marched.push_back({e(0, 2), e(0, 3), e(1, 3), e(1, 2)});
      }
    }
  }
  if (marched.empty())
    throw std::invalid_argument("distance_field: the indicator does not change sign in the box at the finest cells");
  std::vector<P3> crossing(edges.size());
  const double tolerance = 1e-13 * out.finest_size;
#pragma omp parallel for schedule(dynamic, 64)
  for (std::size_t i = 0; i < edges.size(); ++i) {
    Vec a = L.point(edges[i].in), b = L.point(edges[i].out);
    for (int it = 0; it < 80 && (a - b).norm() > tolerance; ++it) {
      const Vec m = (a + b) / 2;
      (inside(m) ? a : b) = m;
    }
    crossing[i] = padded_3d((a + b) / 2);
  }
  std::vector<std::array<P3, 3>> facets;
  for (const auto& m : marched) {
    const auto p = [&](int k) { return crossing[static_cast<std::size_t>(m[static_cast<std::size_t>(k)])]; };
    if (dim == 2) facets.push_back({p(0), p(1), P3::Zero()});
    else {
      facets.push_back({p(0), p(1), p(2)});
      if (m[3] >= 0) facets.push_back({p(0), p(2), p(3)});
    }
  }
  out.surface_facets = facets.size();
  const FacetDistance surface(std::move(facets), dim);

  // Background cells and nodes (shared through their lattice keys).
  const ElementType type = dim == 2 ? ElementType::Quadrilateral : ElementType::Hexahedron;
  const ReferenceElement& ref = reference_element(type, o.order);
  CellBlock block;
  block.type = type;
  block.order = o.order;
  std::unordered_map<std::int64_t, std::int32_t> node_of;
  std::vector<std::array<std::int64_t, 3>> node_lattice;
  std::vector<std::int32_t> cell_nodes(static_cast<std::size_t>(ref.n_nodes()));
  for (const Cell& c : cells) {
    const std::int64_t s = L.scale(c.level);
    for (int a = 0; a < ref.n_nodes(); ++a) {
      std::array<std::int64_t, 3> I{0, 0, 0};
      for (int k = 0; k < dim; ++k)  // ξ ∈ [−1, 1] at multiples of 2/order
        I[static_cast<std::size_t>(k)] = c.ijk[static_cast<std::size_t>(k)] * s + std::llround((ref.nodes(k, a) + 1) / 2 * static_cast<double>(s));
      const auto [it, fresh] = node_of.try_emplace(L.key(I), static_cast<std::int32_t>(node_lattice.size()));
      if (fresh) node_lattice.push_back(I);
      cell_nodes[static_cast<std::size_t>(a)] = it->second;
    }
    block.push_back(cell_nodes.data(), 0);
  }
  Mesh& mesh = out.background;
  mesh.dim = dim;
  mesh.x.resize(dim, static_cast<Eigen::Index>(node_lattice.size()));
  mesh.node_tags.resize(node_lattice.size());
  out.values.resize(static_cast<Eigen::Index>(node_lattice.size()));
#pragma omp parallel for schedule(dynamic, 256)
  for (std::size_t n = 0; n < node_lattice.size(); ++n) {
    const Vec x = L.point(node_lattice[n]);
    mesh.x.col(static_cast<Eigen::Index>(n)) = x;
    mesh.node_tags[n] = static_cast<std::int64_t>(n) + 1;
    const double d = surface.distance(padded_3d(x));
    out.values[static_cast<Eigen::Index>(n)] = inside(x) ? -d : d;
  }
  mesh.cells.push_back(std::move(block));
  return out;
}

}  // namespace meshmorph
