// SPDX-License-Identifier: MIT
#include "meshmorph/fem/structured.h"

#include <algorithm>
#include <array>

#include "meshmorph/error.h"
#include "meshmorph/fem/elevate.h"
#include "meshmorph/mesh/topology.h"

namespace meshmorph {
namespace {

// Side tag of a boundary facet from its centroid: left/right/bottom/top/front/back.
std::int32_t side_of(const Eigen::VectorXd& c, int dim) {
  const double eps = 1e-12;
  if (c(0) < eps) return 1;
  if (c(0) > 1 - eps) return 2;
  const int vertical = dim - 1;  // y in 2D, z in 3D
  if (c(vertical) < eps) return 3;
  if (c(vertical) > 1 - eps) return 4;
  return c(1) < eps ? 5 : 6;
}

}  // namespace

Mesh structured_mesh(ElementType type, int order, int n) {
  MESHMORPH_CHECK(n >= 1, "structured_mesh needs n >= 1");
  Mesh m;
  m.dim = topological_dim(type);
  MESHMORPH_CHECK(m.dim >= 2, "structured_mesh makes cells of dimension 2 or 3");
  const int n1 = n + 1, nz = m.dim == 3 ? n1 : 1;
  const auto id = [&](int i, int j, int k) { return static_cast<std::int32_t>(i + n1 * (j + n1 * k)); };
  // Pyramids: one more node at the centre of each cube, the apex of its six pyramids.
  const bool pyramids = type == ElementType::Pyramid;
  const auto centre = [&](int i, int j, int k) { return static_cast<std::int32_t>(n1 * n1 * n1 + i + n * (j + n * k)); };
  m.x.resize(m.dim, static_cast<Eigen::Index>(n1) * n1 * nz + (pyramids ? n * n * n : 0));
  if (pyramids)
    for (int k = 0; k < n; ++k)
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) m.x.col(centre(i, j, k)) << (i + 0.5) / n, (j + 0.5) / n, (k + 0.5) / n;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < n1; ++j)
      for (int i = 0; i < n1; ++i) {
        m.x(0, id(i, j, k)) = double(i) / n;
        m.x(1, id(i, j, k)) = double(j) / n;
        if (m.dim == 3) m.x(2, id(i, j, k)) = double(k) / n;
      }
  m.node_tags.resize(m.n_nodes());
  for (std::size_t i = 0; i < m.n_nodes(); ++i) m.node_tags[i] = static_cast<std::int64_t>(i + 1);

  CellBlock cells{type, 1, {}, {}, {}};
  for (int k = 0; k < (m.dim == 3 ? n : 1); ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const auto v = [&](int a, int b, int c) { return id(i + a, j + b, k + c); };
        switch (type) {
          case ElementType::Triangle: {
            const std::array<std::int32_t, 3> t0{v(0, 0, 0), v(1, 0, 0), v(1, 1, 0)}, t1{v(0, 0, 0), v(1, 1, 0), v(0, 1, 0)};
            cells.push_back(t0.data(), 1);
            cells.push_back(t1.data(), 1);
            break;
          }
          case ElementType::Quadrilateral: {
            const std::array<std::int32_t, 4> q{v(0, 0, 0), v(1, 0, 0), v(1, 1, 0), v(0, 1, 0)};
            cells.push_back(q.data(), 1);
            break;
          }
          case ElementType::Hexahedron: {
            const std::array<std::int32_t, 8> h{v(0, 0, 0), v(1, 0, 0), v(1, 1, 0), v(0, 1, 0),
                                                v(0, 0, 1), v(1, 0, 1), v(1, 1, 1), v(0, 1, 1)};
            cells.push_back(h.data(), 1);
            break;
          }
          case ElementType::Prism: {  // the cube's two halves across the diagonal of its base
            const std::array<std::int32_t, 6> p0{v(0, 0, 0), v(1, 0, 0), v(1, 1, 0), v(0, 0, 1), v(1, 0, 1), v(1, 1, 1)},
                p1{v(0, 0, 0), v(1, 1, 0), v(0, 1, 0), v(0, 0, 1), v(1, 1, 1), v(0, 1, 1)};
            cells.push_back(p0.data(), 1);
            cells.push_back(p1.data(), 1);
            break;
          }
          case ElementType::Pyramid: {  // a face of the cube each, reversed so that the apex is inside
            const std::array<std::int32_t, 8> h{v(0, 0, 0), v(1, 0, 0), v(1, 1, 0), v(0, 1, 0),
                                                v(0, 0, 1), v(1, 0, 1), v(1, 1, 1), v(0, 1, 1)};
            for (const auto& f : corner_facets(ElementType::Hexahedron)) {
              const std::array<std::int32_t, 5> p{h[f[0]], h[f[3]], h[f[2]], h[f[1]], centre(i, j, k)};
              cells.push_back(p.data(), 1);
            }
            break;
          }
          default: {  // Kuhn: one tet per path 000 → 111 along the axes in each order
            static constexpr std::array<std::array<int, 3>, 6> perms{
                {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}}};
            for (const auto& p : perms) {
              std::array<int, 3> at{0, 0, 0};
              std::array<std::int32_t, 4> t{};
              t[0] = v(0, 0, 0);
              for (int s = 0; s < 3; ++s) {
                at[static_cast<std::size_t>(p[static_cast<std::size_t>(s)])] = 1;
                t[static_cast<std::size_t>(s + 1)] = v(at[0], at[1], at[2]);
              }
              // Odd permutations give negatively oriented tets: swap two vertices.
              const bool odd = (p[0] == 0 && p[1] == 2) || (p[0] == 1 && p[1] == 0) || (p[0] == 2 && p[1] == 1);
              if (odd) std::swap(t[1], t[2]);
              cells.push_back(t.data(), 1);
            }
          }
        }
      }
  m.cells.push_back(std::move(cells));

  const auto topo = build_topology(m);
  // One facet block per facet family (prisms have triangles and quadrilaterals), in the order
  // of the cell's facets.
  std::vector<CellBlock> blocks;
  for (std::size_t f = 0; f < corner_facets(type).size(); ++f) {
    const ElementType ft = facet_type(type, static_cast<int>(f));
    if (std::none_of(blocks.begin(), blocks.end(), [&](const CellBlock& b) { return b.type == ft; }))
      blocks.push_back(CellBlock{ft, 1, {}, {}, {}});
  }
  for (auto f : topo.boundary_facets) {
    const auto& where = topo.facets[static_cast<std::size_t>(f)][0];
    const auto [b, c] = topo.locate(where.cell);
    const auto& local = corner_facets(type)[static_cast<std::size_t>(where.local)];
    std::array<std::int32_t, 4> v{};
    Eigen::VectorXd centroid = Eigen::VectorXd::Zero(m.dim);
    for (std::size_t i = 0; i < local.size(); ++i) {
      v[i] = m.cells[b].cell(c)[local[i]];
      centroid += m.x.col(v[i]) / double(local.size());
    }
    const ElementType ft = facet_type(type, where.local);
    std::find_if(blocks.begin(), blocks.end(), [&](const CellBlock& blk) { return blk.type == ft; })->push_back(v.data(), side_of(centroid, m.dim));
  }
  for (auto& b : blocks)
    if (b.n_cells() > 0) m.facets.push_back(std::move(b));

  m.groups.push_back({m.dim, 1, "domain"});
  const std::array<const char*, 6> names{"left", "right", "bottom", "top", "front", "back"};
  for (int s = 0; s < 2 * m.dim; ++s) m.groups.push_back({m.dim - 1, s + 1, names[static_cast<std::size_t>(s)]});
  return order == 1 ? m : elevate_order(m, order);
}

}  // namespace meshmorph
