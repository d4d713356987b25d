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

// Gmsh's prism (P1, and the complete 18-node P2: type 13) and pyramid (P1: 7, P2: 14), as
// gmsh::model::mesh::getElementProperties gives them: the triangle (u, v) × w ∈ [−1, 1]; the
// base [−1, 1]² at w = 0 with the apex at (0, 0, 1). P2 prism: corners, the edges (0 1) (0 2)
// (0 3) (1 2) (1 4) (2 5) (3 4) (3 5) (4 5), the quadrilateral faces (0 1 4 3) (0 2 5 3) (1 2 5 4).
constexpr double k_prism2[18][3] = {{0, 0, -1},  {1, 0, -1},  {0, 1, -1},  {0, 0, 1},   {1, 0, 1},   {0, 1, 1},
                                    {.5, 0, -1}, {0, .5, -1}, {0, 0, 0},   {.5, .5, -1}, {1, 0, 0},   {0, 1, 0},
                                    {.5, 0, 1},  {0, .5, 1},  {.5, .5, 1}, {.5, 0, 0},  {0, .5, 0},  {.5, .5, 0}};
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
    case ElementType::Prism: return table_nodes(k_prism2, n_nodes_of(type, p));
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
