// SPDX-License-Identifier: MIT
#include "meshmorph/mesh/pillow.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

#include <Eigen/LU>
#include <gtest/gtest.h>

namespace meshmorph {
namespace {

// The unit square / cube in n^d linear quadrilaterals / hexahedra (Gmsh node order), with
// node tags 1..N, a node field "x" (the first coordinate) and the boundary as facet elements.
Mesh grid(int d, int n) {
  Mesh m;
  m.dim = d;
  const int p = n + 1, nodes = d == 2 ? p * p : p * p * p;
  m.x.resize(d, nodes);
  for (int i = 0; i < nodes; ++i) {
    m.x(0, i) = static_cast<double>(i % p) / n;
    m.x(1, i) = static_cast<double>((i / p) % p) / n;
    if (d == 3) m.x(2, i) = static_cast<double>(i / (p * p)) / n;
    m.node_tags.push_back(i + 1);
  }
  m.node_fields["x"] = m.x.row(0).transpose();
  CellBlock cells, facets;
  cells.type = d == 2 ? ElementType::Quadrilateral : ElementType::Hexahedron;
  facets.type = d == 2 ? ElementType::Line : ElementType::Quadrilateral;
  const auto id = [&](int i, int j, int k) { return i + p * (j + p * k); };
  for (int k = 0; k < (d == 2 ? 1 : n); ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        std::vector<std::int32_t> v = {id(i, j, k), id(i + 1, j, k), id(i + 1, j + 1, k), id(i, j + 1, k)};
        if (d == 3)
          for (int a = 0; a < 4; ++a) v.push_back(v[static_cast<std::size_t>(a)] + p * p);
        cells.push_back(v.data(), 1);
      }
  m.cells.push_back(cells);
  if (d == 2)
    for (int i = 0; i < n; ++i)
      for (const std::array<std::int32_t, 2> e : {std::array{id(i, 0, 0), id(i + 1, 0, 0)}, std::array{id(n, i, 0), id(n, i + 1, 0)},
                                                   std::array{id(i + 1, n, 0), id(i, n, 0)}, std::array{id(0, i + 1, 0), id(0, i, 0)}})
        facets.push_back(e.data(), 2);
  m.facets.push_back(facets);
  return m;
}

// det J of a linear quadrilateral / hexahedron at the reference point (u, v, w) ∈ [0,1]^d.
double det_at(const Mesh& m, const std::int32_t* v, double u, double s, double w) {
  const int d = m.dim;
  Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
  const int corners = d == 2 ? 4 : 8;
  const int bits[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  const double t[3] = {u, s, w};
  for (int a = 0; a < corners; ++a)
    for (int k = 0; k < d; ++k) {
      double g = 1.0;
      for (int l = 0; l < d; ++l) {
        const double f = bits[a][l] ? t[l] : 1.0 - t[l];
        g *= l == k ? (bits[a][l] ? 1.0 : -1.0) : f;
      }
      for (int r = 0; r < d; ++r) J(r, k) += g * m.x(r, v[a]);
    }
  return d == 2 ? J.topLeftCorner<2, 2>().determinant() : J.determinant();
}

// Total measure (Gauss rule, exact for these maps) and the smallest det J at the corners and
// the Gauss points of every cell.
std::pair<double, double> measure_and_min_det(const Mesh& m) {
  const double g[2] = {0.5 - 0.5 / std::sqrt(3.0), 0.5 + 0.5 / std::sqrt(3.0)};
  double measure = 0.0, lo = 1e300;
  const CellBlock& b = m.cells[0];
  for (std::size_t c = 0; c < b.n_cells(); ++c) {
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j)
        for (int k = 0; k < (m.dim == 2 ? 1 : 2); ++k) {
          const double det = det_at(m, b.cell(c), g[i], g[j], g[k]);
          measure += det / (m.dim == 2 ? 4.0 : 8.0);
          lo = std::min(lo, det);
        }
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j)
        for (int k = 0; k < (m.dim == 2 ? 1 : 2); ++k) lo = std::min(lo, det_at(m, b.cell(c), i, j, k));
  }
  return {measure, lo};
}

// The facets of cells of `side` whose neighbour is not of `side`, flagged per cell.
std::vector<std::vector<std::uint8_t>> surface_of(const Topology& t, const std::vector<std::uint8_t>& side, bool boundary) {
  std::vector<std::vector<std::uint8_t>> marked(side.size());
  for (std::size_t c = 0; c < side.size(); ++c) {
    if (!side[c]) continue;
    for (auto k = t.cell_neighbor_offset[c]; k < t.cell_neighbor_offset[c + 1]; ++k) {
      const std::int32_t o = t.cell_neighbors[static_cast<std::size_t>(k)];
      marked[c].push_back(o >= 0 ? !side[static_cast<std::size_t>(o)] : boundary);
    }
  }
  return marked;
}

// A staircase ball in a grid (cells whose centre lies within r of the middle): pillowing its
// inside leaves a conforming, valid mesh of the same measure in which every flagged facet
// lies in a new cell of its own and no cell of the side holds two facets of the surface.
TEST(Pillow, LinesAStaircaseWithOneLayerOfConformingCells) {
  for (const int d : {2, 3}) {
    SCOPED_TRACE(d);
    const Mesh mesh = grid(d, 6);
    const Topology topo = build_topology(mesh);
    std::vector<std::uint8_t> inside(mesh.n_cells());
    for (std::size_t c = 0; c < inside.size(); ++c) {
      Eigen::VectorXd centre = Eigen::VectorXd::Zero(d);
      for (int a = 0; a < (d == 2 ? 4 : 8); ++a) centre += mesh.x.col(mesh.cells[0].cell(c)[a]);
      centre /= d == 2 ? 4 : 8;
      inside[c] = (centre.array() - 0.5).matrix().norm() < 0.3;
    }
    const std::vector<std::vector<std::uint8_t>> marked = surface_of(topo, inside, false);
    std::size_t flagged = 0, crowded = 0;
    for (const auto& m : marked) {
      flagged += static_cast<std::size_t>(std::ranges::count(m, 1));
      crowded += std::ranges::count(m, 1) >= 2;
    }
    ASSERT_GT(crowded, 0u);
    const Pillowed p = pillow(mesh, topo, marked);
    EXPECT_EQ(p.added, flagged);
    EXPECT_EQ(p.mesh.n_cells(), mesh.n_cells() + flagged);
    const Topology after = build_topology(p.mesh);  // throws if a facet had three cells
    EXPECT_EQ(after.boundary_facets.size(), topo.boundary_facets.size()) << "a hole inside";
    const auto [measure, min_det] = measure_and_min_det(p.mesh);
    EXPECT_NEAR(measure, 1.0, 1e-12);
    EXPECT_GT(min_det, 0.0);
    // The new side (old inside cells and the layer): its surface is the flagged facets, each in
    // a new cell, one per cell.
    std::vector<std::uint8_t> side(p.mesh.n_cells());
    for (std::size_t c = 0; c < side.size(); ++c) side[c] = inside[static_cast<std::size_t>(p.source[c])];
    const std::vector<std::vector<std::uint8_t>> now = surface_of(after, side, false);
    for (std::size_t c = 0; c < side.size(); ++c) {
      const auto n = std::ranges::count(now[c], 1);
      if (p.surface_facet[c] >= 0) {
        EXPECT_EQ(n, 1) << "cell " << c;
        EXPECT_EQ(now[c][static_cast<std::size_t>(p.surface_facet[c])], 1) << "cell " << c;
      } else {
        EXPECT_EQ(n, 0) << "cell " << c;
      }
    }
    // New nodes copy their node's tag order and field value at the copy's origin.
    EXPECT_EQ(p.mesh.node_tags.size(), p.mesh.n_nodes());
    EXPECT_EQ(p.mesh.node_tags.back(), static_cast<std::int64_t>(p.mesh.n_nodes()));
  }
}

// A trimmed boundary that meets the outer boundary: the copies of nodes on the outer
// boundary slide along it, new nodes take their node's field values, the facet elements
// follow their cells, and the measure stays.
TEST(Pillow, CopiesOnTheOuterBoundaryStayOnIt) {
  Mesh mesh = grid(2, 4);
  mesh.node_fields["y"] = mesh.x.row(1).transpose();
  const Topology topo = build_topology(mesh);
  std::vector<std::uint8_t> kept(mesh.n_cells());
  for (std::size_t c = 0; c < kept.size(); ++c) kept[c] = c % 4 + c / 4 < 4;  // a staircase in the corner (0, 0)
  const Pillowed p = pillow(mesh, topo, surface_of(topo, kept, false));
  EXPECT_EQ(p.added, 6u);
  const auto [measure, min_det] = measure_and_min_det(p.mesh);
  EXPECT_NEAR(measure, 1.0, 1e-12);
  EXPECT_GT(min_det, 0.0);
  for (Eigen::Index i = static_cast<Eigen::Index>(mesh.n_nodes()); i < p.mesh.x.cols(); ++i)
    for (int k = 0; k < 2; ++k)
      if (p.mesh.node_fields.at(k == 0 ? "x" : "y")[i] == 0.0) {
        EXPECT_EQ(p.mesh.x(k, i), 0.0) << "node " << i;
      }
  const Topology after = build_topology(p.mesh);
  ASSERT_EQ(p.mesh.facets[0].n_cells(), mesh.facets[0].n_cells());
  for (std::size_t k = 0; k < p.mesh.facets[0].n_cells(); ++k)
    for (int a = 0; a < 2; ++a)
      EXPECT_TRUE(std::ranges::binary_search(after.boundary_corners, p.mesh.facets[0].cell(k)[a])) << "facet " << k;
}

// Six of the eight cubes around the centre of a 2x2x2 grid (two opposite ones left out): the
// side lies on both sides of the centre, whose copy cannot move into every cube, so the centre
// is a saddle and pillow() refuses; with every cube around it on the side, no saddle is left.
TEST(Pillow, OppositeOctantsMakeASaddle) {
  const Mesh mesh = grid(3, 2);
  const Topology topo = build_topology(mesh);
  std::vector<std::uint8_t> side(8, 1);
  side[0] = side[7] = 0;
  const std::vector<std::vector<std::uint8_t>> marked = surface_of(topo, side, false);
  EXPECT_EQ(pillow_saddles(mesh, topo, marked), std::vector<std::int32_t>{13});
  EXPECT_THROW(pillow(mesh, topo, marked), std::invalid_argument);
  side[0] = 1;
  EXPECT_TRUE(pillow_saddles(mesh, topo, surface_of(topo, side, false)).empty());
  EXPECT_EQ(pillow(mesh, topo, surface_of(topo, side, false)).added, 3u);
}

}  // namespace
}  // namespace meshmorph
