// SPDX-License-Identifier: MIT
#include "meshmorph/io/solver_ordering.h"

#include <cgnslib.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <map>
#include <mutex>
#include <stdexcept>

#include "meshmorph/fem/reference_element.h"

namespace meshmorph {
namespace {

using V = Eigen::Vector3d;
using Points = std::vector<V>;

// Nodes strictly inside the segment a→b of an order-p element, from a to b.
void edge(Points& out, const V a, const V b, int p) {  // by value: a and b may live in out
  for (int i = 1; i < p; ++i) out.push_back(a + (b - a) * (static_cast<double>(i) / p));
}

Points triangle(int p);

// The nodes inside triangle (a, b, c) of order p: the triangle of order p − 3 shrunk into it,
// its first node nearest a.
void triangle_inside(Points& out, const V& a, const V& b, const V& c, int p) {
  if (p < 3) return;
  const double scale = static_cast<double>(p - 3) / p;
  for (const V& q : triangle(p - 3)) {
    const double u = q(0) * scale + 1.0 / p, v = q(1) * scale + 1.0 / p;
    out.push_back((1 - u - v) * a + u * b + v * c);
  }
}

// The unit triangle of order p (order 0: its centroid): corners, edges, inside.
Points triangle(int p) {
  if (p == 0) return {V(1.0 / 3, 1.0 / 3, 0)};
  Points out{V(0, 0, 0), V(1, 0, 0), V(0, 1, 0)};
  for (int i = 0; i < 3; ++i) edge(out, out[i], out[(i + 1) % 3], p);
  const V a = out[0], b = out[1], c = out[2];
  triangle_inside(out, a, b, c, p);
  return out;
}

// The nodes inside quadrilateral (a, b, c, d) of order p: on [−1, 1]², the rings of the
// quadrilateral shrunk by (p − 2)/p, each ring's nodes from its corners on, then the centre.
void quad_inside(Points& out, const V& a, const V& b, const V& c, const V& d, int p) {
  Points uv;
  const std::array<V, 4> corner{V(-1, -1, 0), V(1, -1, 0), V(1, 1, 0), V(-1, 1, 0)};
  if (p > 2) {
    const double scale = static_cast<double>(p - 2) / p;
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < p - 2; ++j) {
        const double t = static_cast<double>(j) / (p - 2);
        uv.push_back((corner[i] * (1 - t) + corner[(i + 1) % 4] * t) * scale);
      }
  }
  if (p % 2 == 0) uv.push_back(V::Zero());
  for (const V& q : uv)
    out.push_back(((1 - q(0)) * (1 - q(1)) * a + (1 + q(0)) * (1 - q(1)) * b + (1 + q(0)) * (1 + q(1)) * c +
                   (1 - q(0)) * (1 + q(1)) * d) / 4);
}

Points tetrahedron(int p) {
  if (p == 0) return {V(0.25, 0.25, 0.25)};
  Points v{V(0, 0, 0), V(1, 0, 0), V(0, 1, 0), V(0, 0, 1)};
  Points out = v;
  for (int i = 0; i < 3; ++i) edge(out, v[i], v[(i + 1) % 3], p);
  for (int i = 0; i < 3; ++i) edge(out, v[i], v[3], p);
  triangle_inside(out, v[0], v[1], v[2], p);
  for (int i = 0; i < 3; ++i) triangle_inside(out, v[i], v[(i + 1) % 3], v[3], p);
  if (p >= 4) {
    const double scale = static_cast<double>(p - 4) / p;
    for (const V& q : tetrahedron(p - 4)) out.push_back(q * scale + V::Constant(1.0 / p));
  }
  return out;
}

// Hexahedra and prisms, the base (a quadrilateral or a triangle) raised from z = −1 to 1: the
// base's corners, the top's, base edges, rising edges, top edges, base face, side faces, top
// face, then the inside level by level up the rising edges.
Points extruded(const Points& base, int p) {
  const std::size_t n = base.size();
  Points v = base, rise[4];
  for (const V& b : base) v.emplace_back(b(0), b(1), 1.0);
  const auto inside = [&](Points& out, const V& a, const V& b, const V& c, const V& d) {
    n == 4 ? quad_inside(out, a, b, c, d, p) : triangle_inside(out, a, b, c, p);
  };
  Points out = v;
  for (std::size_t i = 0; i < n; ++i) edge(out, v[i], v[(i + 1) % n], p);
  for (std::size_t i = 0; i < n; ++i) {
    edge(rise[i], v[i], v[i + n], p);
    out.insert(out.end(), rise[i].begin(), rise[i].end());
  }
  for (std::size_t i = 0; i < n; ++i) edge(out, v[i + n], v[(i + 1) % n + n], p);
  inside(out, v[0], v[1], v[2], v[3 % n]);
  for (std::size_t i = 0; i < n; ++i) quad_inside(out, v[i], v[(i + 1) % n], v[(i + 1) % n + n], v[i + n], p);
  inside(out, v[n], v[n + 1], v[n + 2], v[n + 3 % n]);
  for (int k = 0; k < p - 1; ++k) inside(out, rise[0][k], rise[1][k], rise[2][k], rise[3 % n][k]);
  return out;
}

Points pyramid(int p) {  // orders 1 and 2: corners, base edges, rising edges, base centre
  Points v{V(-1, -1, 0), V(1, -1, 0), V(1, 1, 0), V(-1, 1, 0), V(0, 0, 1)};
  Points out = v;
  for (int i = 0; i < 4; ++i) edge(out, v[i], v[(i + 1) % 4], p);
  for (int i = 0; i < 4; ++i) edge(out, v[i], v[4], p);
  quad_inside(out, v[0], v[1], v[2], v[3], p);
  return out;
}

Points cgns_points(ElementType type, int p) {
  switch (type) {
    case ElementType::Point: return {V::Zero()};
    case ElementType::Line: {
      Points out{V(-1, 0, 0), V(1, 0, 0)};
      edge(out, out[0], out[1], p);
      return out;
    }
    case ElementType::Triangle: return triangle(p);
    case ElementType::Quadrilateral: {
      Points out{V(-1, -1, 0), V(1, -1, 0), V(1, 1, 0), V(-1, 1, 0)};
      for (int i = 0; i < 4; ++i) edge(out, out[i], out[(i + 1) % 4], p);
      const Points c(out.begin(), out.begin() + 4);
      quad_inside(out, c[0], c[1], c[2], c[3], p);
      return out;
    }
    case ElementType::Tetrahedron: return tetrahedron(p);
    case ElementType::Hexahedron: return extruded({V(-1, -1, -1), V(1, -1, -1), V(1, 1, -1), V(-1, 1, -1)}, p);
    case ElementType::Prism: return extruded({V(0, 0, -1), V(1, 0, -1), V(0, 1, -1)}, p);
    case ElementType::Pyramid: return pyramid(p);
  }
  return {};
}

// perm[i] = the reference node at points[i]; lattice points of order p lie on multiples of
// 1/(2p) in every reference cell.
std::vector<int> match(ElementType type, int order, const Points& points) {
  const ReferenceElement& ref = reference_element(type, order);
  const auto key = [&](const V& x) {
    std::array<long, 3> k{};
    for (int d = 0; d < 3; ++d) k[static_cast<std::size_t>(d)] = std::lround(x(d) * 2 * order);
    return k;
  };
  std::map<std::array<long, 3>, int> index;
  for (int i = 0; i < ref.n_nodes(); ++i) {
    V x = V::Zero();
    x.head(ref.nodes.rows()) = ref.nodes.col(i);
    index[key(x)] = i;
  }
  if (static_cast<int>(points.size()) != ref.n_nodes() || index.size() != points.size())
    throw std::logic_error("solver ordering: node sets of " + std::string(name_of(type)) + " differ");
  std::vector<int> perm;
  for (const V& x : points) {
    const auto it = index.find(key(x));
    if (it == index.end()) throw std::logic_error("solver ordering: unmatched node");
    perm.push_back(it->second);
  }
  return perm;
}

const std::vector<int>& cached(bool exodus, ElementType type, int order) {
  static std::mutex mutex;
  static std::map<std::tuple<bool, int, int>, std::vector<int>> cache;
  const std::lock_guard lock(mutex);
  const auto key = std::tuple{exodus, static_cast<int>(type), order};
  auto it = cache.find(key);
  if (it != cache.end()) return it->second;
  Points points = cgns_points(type, order);
  if (exodus && type == ElementType::Hexahedron && order == 2) {
    // CGNS: faces -z, -y, +x, +y, -x, +z, centre; Exodus: centre, -z, +z, -x, +x, -y, +y.
    const Points f(points.begin() + 20, points.end());
    std::copy_n(Points{f[6], f[0], f[5], f[4], f[2], f[1], f[3]}.begin(), 7, points.begin() + 20);
  }
  return cache.emplace(key, match(type, order, points)).first->second;
}

constexpr std::array<std::array<int, 5>, 8> k_cgns_types{{
    {NODE, NODE, NODE, NODE, NODE},
    {0, BAR_2, BAR_3, BAR_4, BAR_5},
    {0, TRI_3, TRI_6, TRI_10, TRI_15},
    {0, QUAD_4, QUAD_9, QUAD_16, QUAD_25},  // (order 4: the faces of quartic prisms)
    {0, TETRA_4, TETRA_10, TETRA_20, TETRA_35},
    {0, HEXA_8, HEXA_27, HEXA_64, 0},
    {0, PENTA_6, PENTA_18, PENTA_40, PENTA_75},
    {0, PYRA_5, PYRA_14, 0, 0},
}};

}  // namespace

int cgns_element_type(ElementType type, int order) {
  if (type == ElementType::Point) return NODE;
  if (order < 1 || order > 4) return 0;
  return k_cgns_types[static_cast<std::size_t>(type)][static_cast<std::size_t>(order)];
}

std::optional<TypeOrder> cgns_type_order(int cgns_type) {
  if (cgns_type == NODE) return TypeOrder{ElementType::Point, 1};
  for (std::size_t t = 1; t < k_cgns_types.size(); ++t)
    for (int p = 1; p <= 4; ++p)
      if (k_cgns_types[t][static_cast<std::size_t>(p)] == cgns_type && cgns_type != 0)
        return TypeOrder{static_cast<ElementType>(t), p};
  return std::nullopt;
}

Eigen::MatrixXd cgns_reference_points(ElementType type, int order) {
  const Points pts = cgns_points(type, order);
  const int d = std::max(1, topological_dim(type));
  Eigen::MatrixXd m(d, static_cast<Eigen::Index>(pts.size()));
  for (std::size_t i = 0; i < pts.size(); ++i) m.col(static_cast<Eigen::Index>(i)) = pts[i].head(d);
  return m;
}

const std::vector<int>& cgns_to_gmsh_permutation(ElementType type, int order) {
  if (cgns_element_type(type, order) == 0) throw std::invalid_argument("cgns_to_gmsh_permutation: CGNS has no such element");
  return cached(false, type, type == ElementType::Point ? 1 : order);
}

const std::vector<int>& exodus_to_gmsh_permutation(ElementType type, int order) {
  if (exodus_element_name(type, order).empty()) throw std::invalid_argument("exodus_to_gmsh_permutation: Exodus has no such element");
  return cached(true, type, type == ElementType::Point ? 1 : order);
}

std::string exodus_element_name(ElementType type, int order) {
  if (type == ElementType::Point) return "SPHERE";
  if (order < 1 || order > 2 || (type == ElementType::Pyramid && order > 2)) return {};
  static const char* const base[] = {"", "BAR", "TRI", "QUAD", "TETRA", "HEX", "WEDGE", "PYRAMID"};
  return base[static_cast<int>(type)] + std::to_string(n_nodes_of(type, order));
}

std::optional<TypeOrder> exodus_type_order(std::string_view name, int nodes) {
  std::string s;
  for (const char c : name)
    if (std::isalpha(static_cast<unsigned char>(c))) s += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  static const std::pair<const char*, ElementType> names[] = {
      {"SPHERE", ElementType::Point},   {"BAR", ElementType::Line},          {"BEAM", ElementType::Line},
      {"TRUSS", ElementType::Line},     {"EDGE", ElementType::Line},         {"TRI", ElementType::Triangle},
      {"TRIANGLE", ElementType::Triangle}, {"QUAD", ElementType::Quadrilateral}, {"TET", ElementType::Tetrahedron},
      {"TETRA", ElementType::Tetrahedron}, {"HEX", ElementType::Hexahedron},  {"WEDGE", ElementType::Prism},
      {"PYRAMID", ElementType::Pyramid}};
  for (const auto& [n, type] : names) {
    if (s != n) continue;
    if (type == ElementType::Point) return nodes == 1 ? std::optional{TypeOrder{type, 1}} : std::nullopt;
    for (int p = 1; p <= 2; ++p)
      if (n_nodes_of(type, p) == nodes) return TypeOrder{type, p};
  }
  return std::nullopt;
}

const std::vector<std::vector<int>>& exodus_sides(ElementType type) {
  static const std::vector<std::vector<int>> none, tri{{0, 1}, {1, 2}, {2, 0}}, quad{{0, 1}, {1, 2}, {2, 3}, {3, 0}},
      tet{{0, 1, 3}, {1, 2, 3}, {0, 3, 2}, {0, 2, 1}},
      hex{{0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {0, 4, 7, 3}, {0, 3, 2, 1}, {4, 5, 6, 7}},
      wedge{{0, 1, 4, 3}, {1, 2, 5, 4}, {0, 3, 5, 2}, {0, 2, 1}, {3, 4, 5}},
      pyramid{{0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {0, 4, 3}, {0, 3, 2, 1}};
  switch (type) {
    case ElementType::Triangle: return tri;
    case ElementType::Quadrilateral: return quad;
    case ElementType::Tetrahedron: return tet;
    case ElementType::Hexahedron: return hex;
    case ElementType::Prism: return wedge;
    case ElementType::Pyramid: return pyramid;
    default: return none;
  }
}

}  // namespace meshmorph
