// SPDX-License-Identifier: MIT
#pragma once
#include <array>
#include <vector>

#include <Eigen/Core>
#include <Eigen/LU>

#include "meshmorph/fem/validity.h"
#include "meshmorph/mesh/topology.h"

namespace meshmorph::test {

/// A conforming mesh of four families: a unit-cube hexahedron, a pyramid on its top face, a
/// tetrahedron on one of the pyramid's triangles and a prism on the hexahedron's x = 0 face.
/// Its boundary is one group "wall" (tag 1) of triangles and quadrilaterals; the cells are
/// "domain" (tag 1, dimension 3).
inline Mesh mixed_cells_mesh() {
  Mesh m;
  m.dim = 3;
  const std::vector<std::array<double, 3>> x{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},    {0, 0, 1},       {1, 0, 1},
                                             {1, 1, 1}, {0, 1, 1}, {.5, .5, 1.6}, {1.6, .5, 1.3}, {-.6, .5, 0}, {-.6, .5, 1}};
  m.x.resize(3, static_cast<Eigen::Index>(x.size()));
  for (std::size_t j = 0; j < x.size(); ++j) m.x.col(static_cast<Eigen::Index>(j)) << x[j][0], x[j][1], x[j][2];
  for (std::size_t j = 0; j < x.size(); ++j) m.node_tags.push_back(static_cast<std::int64_t>(j) + 1);
  const auto add = [&](ElementType t, std::vector<std::int32_t> v) {
    CellBlock b{t, 1, {}, {}, {}};
    b.push_back(v.data(), 1, 1);
    m.cells.push_back(b);
  };
  add(ElementType::Hexahedron, {0, 1, 2, 3, 4, 5, 6, 7});
  add(ElementType::Pyramid, {4, 5, 6, 7, 8});
  add(ElementType::Tetrahedron, {5, 9, 6, 8});
  add(ElementType::Prism, {0, 3, 10, 4, 7, 11});
  const Topology topo = build_topology(m);
  CellBlock tris{ElementType::Triangle, 1, {}, {}, {}}, quads{ElementType::Quadrilateral, 1, {}, {}, {}};
  for (const auto f : topo.boundary_facets) {
    const CellFacet& cf = topo.facets[static_cast<std::size_t>(f)][0];
    const auto [b, c] = topo.locate(cf.cell);
    const auto& local = corner_facets(m.cells[b].type)[static_cast<std::size_t>(cf.local)];
    std::vector<std::int32_t> v;
    for (const int i : local) v.push_back(m.cells[b].cell(c)[i]);
    (v.size() == 3 ? tris : quads).push_back(v.data(), 1, 1);
  }
  m.facets = {tris, quads};
  m.groups = {{3, 1, "domain"}, {2, 1, "wall"}};
  return m;
}

}  // namespace meshmorph::test
