// SPDX-License-Identifier: MIT
#include "meshmorph/fem/reference_element.h"

#include <array>
#include <map>
#include <memory>
#include <mutex>

#include "meshmorph/error.h"
#include "meshmorph/mesh/topology.h"

namespace meshmorph {
namespace {

#include "fem/detail/gmsh_node_lattice.inc"

template <std::size_t D, std::size_t N>
Eigen::MatrixXd from_lattice(const std::array<std::array<int, D>, N>& lattice, int p, bool simplex) {
  Eigen::MatrixXd X(static_cast<Eigen::Index>(D), static_cast<Eigen::Index>(N));
  for (std::size_t j = 0; j < N; ++j)
    for (std::size_t k = 0; k < D; ++k) {
      const double t = double(lattice[j][k]) / p;
      X(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(j)) = simplex ? t : 2.0 * t - 1.0;
    }
  return X;
}

// Gmsh's complete prism of order p (types 6, 13, 90, 91) as lattice points (i, j, k), k along
// w: corners, the interior of the edges (0 1) (0 2) (0 3) (1 2) (1 4) (2 5) (3 4) (3 5) (4 5),
// then the faces (0 2 1) (3 4 5) (0 1 4 3) (0 3 5 2) (1 2 5 4), each the triangle of order
// p − 3 or the quadrilateral of order p − 2 in its own node order, shifted one step in and laid
// along the face's first and last-but-one edge, then the body: the triangle of order p − 3 times
// the segment of order p − 2, the segment fastest. Gmsh 4.8.4's getElementProperties refuses
// types 90 and 91; the meshes it writes of them put their nodes there (tests/data/io).
Eigen::MatrixXd gmsh_nodes(ElementType type, int p);

std::vector<std::array<int, 3>> prism_lattice(int p) {
  const std::array<std::array<int, 3>, 6> c{{{0, 0, 0}, {p, 0, 0}, {0, p, 0}, {0, 0, p}, {p, 0, p}, {0, p, p}}};
  std::vector<std::array<int, 3>> out(c.begin(), c.end());
  if (p < 2) return out;
  const auto along = [&](int a, int b, int i, int j, int d) {  // c[a] + (i (c[b] − c[a]) + j (c[d] − c[a])) / p
    std::array<int, 3> q{};
    for (std::size_t k = 0; k < 3; ++k) q[k] = c[a][k] + (i * (c[b][k] - c[a][k]) + j * (c[d][k] - c[a][k])) / p;
    return q;
  };
  constexpr int edges[9][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 4}, {2, 5}, {3, 4}, {3, 5}, {4, 5}};
  for (const auto& e : edges)
    for (int i = 1; i < p; ++i) out.push_back(along(e[0], e[1], i, 0, e[0]));
  // A facet's own lattice of order q (Gmsh's node order), as integer (i, j) (Point: order 0).
  const auto facet = [](ElementType t, int q) {
    std::vector<std::array<int, 2>> pts;
    if (q == 0) return std::vector<std::array<int, 2>>{{0, 0}};
    const Eigen::MatrixXd X = gmsh_nodes(t, q);
    for (Eigen::Index j = 0; j < X.cols(); ++j) {
      const auto at = [&](double x) { return static_cast<int>(std::lround(t == ElementType::Triangle ? x * q : (x + 1) * q / 2)); };
      pts.push_back({at(X(0, j)), t == ElementType::Line ? 0 : at(X(1, j))});
    }
    return pts;
  };
  constexpr int faces[5][4] = {{0, 2, 1, -1}, {3, 4, 5, -1}, {0, 1, 4, 3}, {0, 3, 5, 2}, {1, 2, 5, 4}};
  for (const auto& f : faces) {
    const bool quad = f[3] >= 0;
    if (!quad && p < 3) continue;
    for (const auto& ij : facet(quad ? ElementType::Quadrilateral : ElementType::Triangle, quad ? p - 2 : p - 3))
      out.push_back(along(f[0], f[1], ij[0] + 1, ij[1] + 1, quad ? f[3] : f[2]));
  }
  if (p < 3) return out;
  for (const auto& ij : facet(ElementType::Triangle, p - 3))
    for (const auto& k : facet(ElementType::Line, p - 2)) out.push_back({ij[0] + 1, ij[1] + 1, k[0] + 1});
  return out;
}

// P2 pyramid (type 14): corners, the edges (0 1) (0 3) (0 4) (1 2) (1 4) (2 3) (2 4) (3 4), the
// base's centre.
constexpr double k_pyramid2[14][3] = {{-1, -1, 0}, {1, -1, 0},    {1, 1, 0},    {-1, 1, 0}, {0, 0, 1},
                                      {0, -1, 0},  {-1, 0, 0},    {-.5, -.5, .5}, {1, 0, 0},  {.5, -.5, .5},
                                      {0, 1, 0},   {.5, .5, .5},  {-.5, .5, .5}, {0, 0, 0}};

Eigen::MatrixXd table_nodes(const double (*x)[3], int n) {
  Eigen::MatrixXd X(3, n);
  for (int j = 0; j < n; ++j) X.col(j) << x[j][0], x[j][1], x[j][2];
  return X;
}

Eigen::MatrixXd gmsh_nodes(ElementType type, int p) {
  switch (type) {
    case ElementType::Point: return Eigen::MatrixXd(0, 1);
    case ElementType::Line: {  // corners first, then the interior from −1 to 1
      Eigen::MatrixXd X(1, p + 1);
      X(0, 0) = -1.0;
      X(0, 1) = 1.0;
      for (int i = 1; i < p; ++i) X(0, i + 1) = -1.0 + 2.0 * i / p;
      return X;
    }
    case ElementType::Triangle: {
      const std::array tables{from_lattice(k_triangle1, 1, true), from_lattice(k_triangle2, 2, true),
                              from_lattice(k_triangle3, 3, true), from_lattice(k_triangle4, 4, true)};
      return tables[static_cast<std::size_t>(p - 1)];
    }
    case ElementType::Quadrilateral: {
      const std::array tables{from_lattice(k_quadrilateral1, 1, false), from_lattice(k_quadrilateral2, 2, false),
                              from_lattice(k_quadrilateral3, 3, false), from_lattice(k_quadrilateral4, 4, false)};
      return tables[static_cast<std::size_t>(p - 1)];
    }
    case ElementType::Tetrahedron: {
      const std::array tables{from_lattice(k_tetrahedron1, 1, true), from_lattice(k_tetrahedron2, 2, true),
                              from_lattice(k_tetrahedron3, 3, true), from_lattice(k_tetrahedron4, 4, true)};
      return tables[static_cast<std::size_t>(p - 1)];
    }
    case ElementType::Hexahedron: {
      const std::array tables{from_lattice(k_hexahedron1, 1, false), from_lattice(k_hexahedron2, 2, false),
                              from_lattice(k_hexahedron3, 3, false), from_lattice(k_hexahedron4, 4, false)};
      return tables[static_cast<std::size_t>(p - 1)];
    }
    case ElementType::Prism: {
      const auto lattice = prism_lattice(p);
      Eigen::MatrixXd X(3, static_cast<Eigen::Index>(lattice.size()));
      for (std::size_t j = 0; j < lattice.size(); ++j)
        X.col(static_cast<Eigen::Index>(j)) << double(lattice[j][0]) / p, double(lattice[j][1]) / p, 2.0 * lattice[j][2] / p - 1.0;
      return X;
    }
    case ElementType::Pyramid: return table_nodes(k_pyramid2, n_nodes_of(type, p));
  }
  return {};
}

// Cell-local indices of the nodes of each facet, in the facet element's ordering: map the
// facet's reference nodes into the cell through the facet corners and match positions.
std::vector<std::vector<int>> trace_tables(const ReferenceElement& cell) {
  std::vector<std::vector<int>> out;
  const auto facets = corner_facets(cell.type);
  for (std::size_t f = 0; f < facets.size(); ++f) {
    const auto& fref = reference_element(facet_type(cell.type, static_cast<int>(f)), cell.order);
    std::vector<int> local;
    for (int j = 0; j < fref.n_nodes(); ++j) {
      const auto w = corner_weights(fref.type, fref.nodes.col(j));
      Eigen::VectorXd x = Eigen::VectorXd::Zero(cell.dim);
      for (std::size_t i = 0; i < facets[f].size(); ++i) x += w(static_cast<Eigen::Index>(i)) * cell.nodes.col(facets[f][i]);
      int match = -1;
      for (int a = 0; a < cell.n_nodes(); ++a)
        if ((cell.nodes.col(a) - x).norm() < 1e-10) match = a;
      MESHMORPH_ASSERT(match >= 0);
      local.push_back(match);
    }
    out.push_back(std::move(local));
  }
  return out;
}

}  // namespace

Eigen::VectorXd corner_weights(ElementType type, const Eigen::VectorXd& xi) {
  static constexpr int k_quad_sign[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
  static constexpr int k_hex_sign[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                                           {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
  switch (type) {
    case ElementType::Point: return Eigen::VectorXd::Ones(1);
    case ElementType::Line: return Eigen::Vector2d((1 - xi(0)) / 2, (1 + xi(0)) / 2);
    case ElementType::Triangle: return Eigen::Vector3d(1 - xi(0) - xi(1), xi(0), xi(1));
    case ElementType::Tetrahedron: return Eigen::Vector4d(1 - xi(0) - xi(1) - xi(2), xi(0), xi(1), xi(2));
    case ElementType::Quadrilateral: {
      Eigen::VectorXd w(4);
      for (int i = 0; i < 4; ++i) w(i) = (1 + k_quad_sign[i][0] * xi(0)) * (1 + k_quad_sign[i][1] * xi(1)) / 4;
      return w;
    }
    case ElementType::Hexahedron: {
      Eigen::VectorXd w(8);
      for (int i = 0; i < 8; ++i)
        w(i) = (1 + k_hex_sign[i][0] * xi(0)) * (1 + k_hex_sign[i][1] * xi(1)) * (1 + k_hex_sign[i][2] * xi(2)) / 8;
      return w;
    }
    case ElementType::Prism: {
      const double l[3] = {1 - xi(0) - xi(1), xi(0), xi(1)}, below = (1 - xi(2)) / 2, above = (1 + xi(2)) / 2;
      return (Eigen::VectorXd(6) << l[0] * below, l[1] * below, l[2] * below, l[0] * above, l[1] * above, l[2] * above)
          .finished();
    }
    case ElementType::Pyramid: {
      // The rational P1 basis of lagrange_basis.h, (1 − w)(1 ± ξ/(1 − w))(1 ± η/(1 − w))/4 and w.
      const double h = 1 - xi(2), u = h > 0 ? xi(0) / h : 0.0, v = h > 0 ? xi(1) / h : 0.0;
      Eigen::VectorXd w(5);
      for (int i = 0; i < 4; ++i) w(i) = h * (1 + k_quad_sign[i][0] * u) * (1 + k_quad_sign[i][1] * v) / 4;
      w(4) = xi(2);
      return w;
    }
  }
  return {};
}

double reference_measure(ElementType type) {
  switch (type) {
    case ElementType::Point:
    case ElementType::Line: return type == ElementType::Point ? 1.0 : 2.0;
    case ElementType::Triangle: return 0.5;
    case ElementType::Quadrilateral: return 4.0;
    case ElementType::Tetrahedron: return 1.0 / 6.0;
    case ElementType::Hexahedron: return 8.0;
    case ElementType::Prism: return 1.0;
    case ElementType::Pyramid: return 4.0 / 3.0;
  }
  return 0.0;
}

const ReferenceElement& reference_element(ElementType type, int order) {
  const bool prism_or_pyramid = type == ElementType::Prism || type == ElementType::Pyramid;
  MESHMORPH_CHECK(order >= 1 && order <= (prism_or_pyramid ? max_order_of(type) : 4),
                  "no reference element of order " + std::to_string(order) + " for " + std::string(name_of(type)));
  // Recursive: building a cell's trace tables asks for its facets' reference elements.
  static std::recursive_mutex mutex;
  static std::map<std::pair<ElementType, int>, std::unique_ptr<ReferenceElement>> cache;
  std::lock_guard lock(mutex);
  auto& slot = cache[{type, order}];
  if (!slot) {
    auto ref = std::make_unique<ReferenceElement>();
    ref->type = type;
    ref->order = order;
    ref->dim = topological_dim(type);
    ref->nodes = gmsh_nodes(type, order);
    ref->facet_nodes = trace_tables(*ref);
    slot = std::move(ref);
  }
  return *slot;
}

}  // namespace meshmorph
