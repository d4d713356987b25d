// SPDX-License-Identifier: MIT
#include "meshmorph/io/vtk_ordering.h"

#include <array>
#include <cmath>
#include <map>
#include <mutex>
#include <stdexcept>
#include <string>

#include "meshmorph/fem/reference_element.h"

namespace meshmorph {
namespace {

using P3 = std::array<int, 3>;  // integer lattice point: parametric coordinate × order

// Nodes strictly inside the segment a→b of lattice length p, from a to b.
void edge(std::vector<P3>& out, const P3& a, const P3& b, int p) {
  for (int i = 1; i < p; ++i) {
    P3 q{};
    for (int k = 0; k < 3; ++k) q[k] = a[k] + (b[k] - a[k]) * i / p;
    out.push_back(q);
  }
}

// VTK's recursive triangle of order p with corners a, b, c (lattice points of a triangle of
// side p): corners, edges a→b, b→c, c→a, then the order p−3 triangle inside.
void triangle(std::vector<P3>& out, P3 a, P3 b, P3 c, int p) {
  if (p < 0) return;
  if (p == 0) {
    out.push_back(a);
    return;
  }
  out.insert(out.end(), {a, b, c});
  edge(out, a, b, p);
  edge(out, b, c, p);
  edge(out, c, a, p);
  if (p < 3) return;
  // The inner triangle's corners move one lattice step from each corner toward the others.
  P3 ia{}, ib{}, ic{};
  for (int k = 0; k < 3; ++k) {
    ia[k] = a[k] + ((b[k] - a[k]) + (c[k] - a[k])) / p;
    ib[k] = b[k] + ((a[k] - b[k]) + (c[k] - b[k])) / p;
    ic[k] = c[k] + ((a[k] - c[k]) + (b[k] - c[k])) / p;
  }
  triangle(out, ia, ib, ic, p - 3);
}

// Interior of face triangle a, b, c (side p): the recursive triangle of order p − 3.
void triangle_face(std::vector<P3>& out, const P3& a, const P3& b, const P3& c, int p) {
  if (p < 3) return;
  std::vector<P3> all;
  triangle(all, a, b, c, p);
  out.insert(out.end(), all.begin() + 3 * p, all.end());
}

void tetrahedron(std::vector<P3>& out, P3 v0, P3 v1, P3 v2, P3 v3, int p) {
  if (p < 0) return;
  if (p == 0) {
    out.push_back(v0);
    return;
  }
  const std::array<P3, 4> v{v0, v1, v2, v3};
  out.insert(out.end(), v.begin(), v.end());
  constexpr int edges[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};
  for (const auto& e : edges) edge(out, v[e[0]], v[e[1]], p);
  // Faces y=0, slanted, x=0, z=0; each listed from the corner its first interior node is
  // nearest to (checked against VTK 9.1's parametric coordinates, tests/data/io).
  constexpr int faces[4][3] = {{0, 1, 3}, {2, 3, 1}, {0, 3, 2}, {0, 2, 1}};
  for (const auto& f : faces) triangle_face(out, v[f[0]], v[f[1]], v[f[2]], p);
  if (p < 4) return;
  std::array<P3, 4> inner{};
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k) {
      int s = 0;
      for (int j = 0; j < 4; ++j) s += v[j][k] - v[i][k];
      inner[i][k] = v[i][k] + s / p;
    }
  tetrahedron(out, inner[0], inner[1], inner[2], inner[3], p - 4);
}

std::vector<P3> lattice(ElementType type, int p) {
  std::vector<P3> out;
  switch (type) {
    case ElementType::Point:
      out.push_back({0, 0, 0});
      break;
    case ElementType::Line:
      out.push_back({0, 0, 0});
      out.push_back({p, 0, 0});
      edge(out, {0, 0, 0}, {p, 0, 0}, p);
      break;
    case ElementType::Triangle:
      triangle(out, {0, 0, 0}, {p, 0, 0}, {0, p, 0}, p);
      break;
    case ElementType::Quadrilateral: {
      const std::array<P3, 4> c{P3{0, 0, 0}, P3{p, 0, 0}, P3{p, p, 0}, P3{0, p, 0}};
      for (const P3& corner : c) out.push_back(corner);  // not insert(): GCC 12's false -Wstringop-overflow
      edge(out, c[0], c[1], p);
      edge(out, c[1], c[2], p);
      edge(out, c[3], c[2], p);
      edge(out, c[0], c[3], p);
      for (int j = 1; j < p; ++j)
        for (int i = 1; i < p; ++i) out.push_back({i, j, 0});
      break;
    }
    case ElementType::Tetrahedron:
      tetrahedron(out, {0, 0, 0}, {p, 0, 0}, {0, p, 0}, {0, 0, p}, p);
      break;
    case ElementType::Hexahedron: {
      std::array<P3, 8> c{};
      for (int i = 0; i < 8; ++i) {
        const int x = (i & 3) == 1 || (i & 3) == 2 ? p : 0;
        const int y = (i & 3) >= 2 ? p : 0;
        c[static_cast<std::size_t>(i)] = {x, y, i >= 4 ? p : 0};
      }
      for (const P3& corner : c) out.push_back(corner);  // not insert(): GCC 12's false -Wstringop-overflow
      constexpr int edges[12][2] = {{0, 1}, {1, 2}, {3, 2}, {0, 3}, {4, 5}, {5, 6}, {7, 6}, {4, 7}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
      for (const auto& e : edges) edge(out, c[e[0]], c[e[1]], p);
      // Faces x=0, x=1, y=0, y=1, z=0, z=1; inside each, the lower free axis runs fastest.
      for (int axis = 0; axis < 3; ++axis)
        for (const int side : {0, p}) {
          const int u = axis == 0 ? 1 : 0;
          const int w = axis == 2 ? 1 : 2;
          for (int j = 1; j < p; ++j)
            for (int i = 1; i < p; ++i) {
              P3 q{};
              q[axis] = side;
              q[u] = i;
              q[w] = j;
              out.push_back(q);
            }
        }
      for (int k = 1; k < p; ++k)
        for (int j = 1; j < p; ++j)
          for (int i = 1; i < p; ++i) out.push_back({i, j, k});
      break;
    }
    case ElementType::Prism: {  // VTK's Lagrange wedge (checked against VTK 9.1 to order 4)
      const std::array<P3, 6> c{P3{0, 0, 0}, P3{p, 0, 0}, P3{0, p, 0}, P3{0, 0, p}, P3{p, 0, p}, P3{0, p, p}};
      for (const P3& corner : c) out.push_back(corner);
      constexpr int edges[9][2] = {{0, 1}, {1, 2}, {2, 0}, {3, 4}, {4, 5}, {5, 3}, {0, 3}, {1, 4}, {2, 5}};
      for (const auto& e : edges) edge(out, c[e[0]], c[e[1]], p);
      triangle_face(out, c[0], c[1], c[2], p);  // both triangles counterclockwise seen from above
      triangle_face(out, c[3], c[4], c[5], p);
      constexpr int faces[3][4] = {{0, 1, 4, 3}, {1, 2, 5, 4}, {2, 0, 3, 5}};  // bilinear from corner 0 of each
      for (const auto& f : faces)
        for (int j = 1; j < p; ++j)
          for (int i = 1; i < p; ++i) {
            P3 q{};
            for (int k = 0; k < 3; ++k)
              q[k] = ((p - j) * ((p - i) * c[f[0]][k] + i * c[f[1]][k]) + j * ((p - i) * c[f[3]][k] + i * c[f[2]][k])) / (p * p);
            out.push_back(q);
          }
      std::vector<P3> inside;  // the base triangle's interior at each level, the triangle fastest
      triangle_face(inside, c[0], c[1], c[2], p);
      for (int k = 1; k < p; ++k)
        for (const P3& q : inside) out.push_back({q[0], q[1], k});
      break;
    }
    case ElementType::Pyramid:  // linear only: base, then apex (VTK's apex is above corner 0 in its pcoords)
      for (const P3& q : {P3{0, 0, 0}, P3{p, 0, 0}, P3{p, p, 0}, P3{0, p, 0}, P3{0, 0, p}}) out.push_back(q);
      break;
  }
  return out;
}

// A Gmsh reference node as a VTK lattice point of order p. Lines, quadrilaterals and
// hexahedra: [−1, 1]^d → [0, 1]^d. Prisms: VTK's Lagrange wedge is Gmsh's prism with
// t = (w + 1)/2 (VTK 9.1 gives it a positive volume so; its classic wedge is another matter,
// vtk_cell_permutation). Pyramids: corner by corner (linear only).
P3 vtk_lattice_point(ElementType type, const Eigen::VectorXd& x, int i, int p) {
  const auto at = [&](double v) { return static_cast<int>(std::lround(v * p)); };
  if (type == ElementType::Pyramid) {
    constexpr std::array<P3, 5> corners{P3{0, 0, 0}, P3{1, 0, 0}, P3{1, 1, 0}, P3{0, 1, 0}, P3{0, 0, 1}};
    const P3& c = corners[static_cast<std::size_t>(i)];
    return {c[0] * p, c[1] * p, c[2] * p};
  }
  if (type == ElementType::Prism) return {at(x(0)), at(x(1)), at((x(2) + 1.0) / 2.0)};
  const bool tensor = is_tensor(type) || type == ElementType::Line;
  P3 q{};
  for (Eigen::Index k = 0; k < x.size(); ++k) q[static_cast<std::size_t>(k)] = at(tensor ? (x(k) + 1.0) / 2.0 : x(k));
  return q;
}

std::vector<int> compute_permutation(ElementType type, int order) {
  if (type == ElementType::Point) return {0};
  const std::vector<P3> vtk = lattice(type, order);
  const ReferenceElement& ref = reference_element(type, order);
  std::map<P3, int> gmsh_index;
  for (int i = 0; i < ref.n_nodes(); ++i) gmsh_index[vtk_lattice_point(type, ref.nodes.col(i), i, order)] = i;
  if (static_cast<int>(vtk.size()) != ref.n_nodes() || gmsh_index.size() != vtk.size())
    throw std::logic_error("vtk_to_gmsh_permutation: node sets of " + std::string(name_of(type)) + " differ");
  std::vector<int> perm;
  for (const P3& q : vtk) {
    const auto it = gmsh_index.find(q);
    if (it == gmsh_index.end()) throw std::logic_error("vtk_to_gmsh_permutation: unmatched VTK node");
    perm.push_back(it->second);
  }
  return perm;
}

}  // namespace

int vtk_cell_type(ElementType type) {
  switch (type) {
    case ElementType::Point: return 1;
    case ElementType::Line: return 68;
    case ElementType::Triangle: return 69;
    case ElementType::Quadrilateral: return 70;
    case ElementType::Tetrahedron: return 71;
    case ElementType::Hexahedron: return 72;
    case ElementType::Prism: return 73;
    case ElementType::Pyramid: return 74;
  }
  return 0;
}

Eigen::MatrixXd vtk_lagrange_points(ElementType type, int order) {
  const std::vector<P3> pts = lattice(type, order);
  const int d = std::max(1, topological_dim(type));
  Eigen::MatrixXd m(d, static_cast<Eigen::Index>(pts.size()));
  for (std::size_t i = 0; i < pts.size(); ++i)
    for (int k = 0; k < d; ++k) m(k, static_cast<Eigen::Index>(i)) = static_cast<double>(pts[i][static_cast<std::size_t>(k)]) / order;
  return m;
}

const std::vector<int>& vtk_to_gmsh_permutation(ElementType type, int order) {
  if (order < 1 || order > 4) throw std::invalid_argument("vtk_to_gmsh_permutation: order must be 1..4");
  static std::mutex mutex;
  static std::map<std::pair<int, int>, std::vector<int>> cache;
  const std::lock_guard lock(mutex);
  const std::pair<int, int> key{static_cast<int>(type), order};
  auto it = cache.find(key);
  if (it == cache.end()) it = cache.emplace(key, compute_permutation(type, order)).first;
  return it->second;
}

const std::vector<int>& vtk_cell_permutation(int vtk_type, ElementType type, int order) {
  static const std::vector<int> k_wedge{0, 2, 1, 3, 5, 4};
  // VTK_QUADRATIC_WEDGE: VTK_WEDGE's corners, then its edges (0 1) (1 2) (2 0) (3 4) (4 5)
  // (5 3) (0 3) (1 4) (2 5), each on Gmsh's edge between the corners it took.
  static const std::vector<int> k_quadratic_wedge{0, 2, 1, 3, 5, 4, 7, 9, 6, 13, 14, 12, 8, 11, 10};
  // VTK_QUADRATIC_PYRAMID: the corners, then the base's edges and the edges to the apex.
  static const std::vector<int> k_quadratic_pyramid{0, 1, 2, 3, 4, 5, 8, 10, 6, 7, 9, 11, 12};
  switch (vtk_type) {
    case 13: return k_wedge;
    case 26: return k_quadratic_wedge;
    case 27: return k_quadratic_pyramid;
    default: return vtk_to_gmsh_permutation(type, order);
  }
}

}  // namespace meshmorph
