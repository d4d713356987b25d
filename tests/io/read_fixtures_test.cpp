// SPDX-License-Identifier: MIT
// Files written by other tools: Gmsh 4.8.4 (tests/data/io/*.geo, see docs/formats.md),
// meshio 5.0.0 (from gmsh_tri6_41a.msh / gmsh_tet4_22a.msh) and VTK 9.1
// (tests/data/io/serendipity_meshes.py).
#include <algorithm>
#include <cmath>
#include <iterator>
#include <string>

#include <gtest/gtest.h>

#include "io/mesh_compare.h"
#include "meshmorph/fem/validity.h"
#include "meshmorph/io/mesh_io.h"

namespace meshmorph {
namespace {

std::string data(const std::string& name) { return std::string(MESHMORPH_TEST_DATA) + "/io/" + name; }

std::size_t count(const std::vector<CellBlock>& blocks, ElementType type, int order) {
  std::size_t n = 0;
  for (const CellBlock& b : blocks) n += b.type == type && b.order == order ? b.n_cells() : 0;
  return n;
}

TEST(ReadFixtures, GmshP2TrianglesInAllFourEncodingsAgree) {
  const Mesh m = read_mesh(data("gmsh_tri6_41a.msh"));
  EXPECT_EQ(m.dim, 2);
  EXPECT_EQ(m.n_nodes(), 277u);
  ASSERT_EQ(m.cells.size(), 1u);
  EXPECT_EQ(m.cells[0].type, ElementType::Triangle);
  EXPECT_EQ(m.cells[0].order, 2);
  EXPECT_EQ(m.cells[0].n_cells(), 121u);
  EXPECT_EQ(count(m.facets, ElementType::Line, 2), 35u);
  EXPECT_EQ(test::sorted_groups(m), (std::vector<std::tuple<int, int, std::string>>{
                                        {1, 20, "hole wall"}, {1, 21, "outer"}, {2, 10, "fluid"}}));
  for (const std::int32_t t : m.cells[0].physical) EXPECT_EQ(t, 10);
  const auto hole = m.find_group("hole wall");
  ASSERT_TRUE(hole.has_value());
  EXPECT_EQ(m.group_nodes(*hole).size(), 2u * 7u);  // a closed curve of 7 P2 edges: 14 nodes
  // Gmsh prints 16 significant digits in ASCII, so ASCII and binary differ by an ulp.
  test::expect_meshes_equal(m, read_mesh(data("gmsh_tri6_22a.msh")));
  // Mesh.SaveParametric: $ParametricNodes, each node with its entity and u (v) after x y z.
  test::expect_meshes_equal(m, read_mesh(data("gmsh_tri6_parametric_22a.msh")));
  for (const char* binary : {"gmsh_tri6_41b.msh", "gmsh_tri6_22b.msh"}) {
    SCOPED_TRACE(binary);
    test::expect_meshes_equal(m, read_mesh(data(binary)), {.tolerance = 1e-15});
  }
}

// gmsh -part 3: the elements name the entities of $PartitionedEntities, where the physical
// tags are; read whole, the mesh has the unpartitioned file's cells and groups.
TEST(ReadFixtures, GmshPartitionedFilesKeepTheirPhysicalGroups) {
  const Mesh whole = read_mesh(data("gmsh_tri6_41a.msh"));
  for (const char* name : {"gmsh_tri6_part3_41a.msh", "gmsh_tri6_part3_41b.msh"}) {
    SCOPED_TRACE(name);
    const Mesh m = read_mesh(data(name));
    EXPECT_EQ(m.n_nodes(), whole.n_nodes());
    EXPECT_EQ(count(m.cells, ElementType::Triangle, 2), 121u);
    EXPECT_EQ(count(m.facets, ElementType::Line, 2), 35u);
    EXPECT_EQ(test::sorted_groups(m), test::sorted_groups(whole));
    for (const CellBlock& b : m.cells)
      for (const std::int32_t t : b.physical) EXPECT_EQ(t, 10);
    for (const char* group : {"hole wall", "outer", "fluid"}) {
      const auto g = m.find_group(group);
      ASSERT_TRUE(g.has_value()) << group;
      EXPECT_EQ(m.group_nodes(*g).size(), whole.group_nodes(*whole.find_group(group)).size()) << group;
    }
  }
}

// Curves in two physical groups each, and the surface (shared_curves.geo): MSH 4.1 gives an
// entity both tags, MSH 2.2 writes its elements once per group. Either way every curve group
// has its nodes, and the cells are held once, with their first tag.
TEST(ReadFixtures, AnEntityInTwoPhysicalGroupsIsInBoth) {
  const Mesh m41 = read_mesh(data("gmsh_tri3_shared_41a.msh"));
  const Mesh m22 = read_mesh(data("gmsh_tri3_shared_22a.msh"));
  for (const Mesh* m : {&m41, &m22}) {
    const auto nodes = [&](const char* name) { return m->group_nodes(*m->find_group(name)); };
    const std::vector<std::int32_t> hole = nodes("hole wall"), outer = nodes("outer"), walls = nodes("walls");
    std::vector<std::int32_t> bottom;  // the nodes of "outer" on y = 0
    for (const std::int32_t v : outer)
      if (m->x(1, v) == 0.0) bottom.push_back(v);
    std::vector<std::int32_t> expected;
    std::set_union(hole.begin(), hole.end(), bottom.begin(), bottom.end(), std::back_inserter(expected));
    EXPECT_EQ(walls, expected);
    EXPECT_GT(hole.size(), 0u);
    EXPECT_GT(bottom.size(), 1u);
    ASSERT_EQ(m->cells.size(), 1u);
    EXPECT_EQ(m->cells[0].n_cells(), 121u);
    for (const std::int32_t t : m->cells[0].physical) EXPECT_EQ(t, 10);
  }
  EXPECT_EQ(m41.n_cells(), m22.n_cells());
  EXPECT_EQ(m41.cells[0].nodes, m22.cells[0].nodes);
}

TEST(ReadFixtures, GmshTetrahedraOrder1And3) {
  const Mesh p3 = read_mesh(data("gmsh_tet20_41b.msh"));
  const Mesh p1 = read_mesh(data("gmsh_tet4_22a.msh"));
  EXPECT_EQ(p3.dim, 3);
  EXPECT_EQ(p1.dim, 3);
  EXPECT_EQ(count(p3.cells, ElementType::Tetrahedron, 3), 101u);
  EXPECT_EQ(count(p1.cells, ElementType::Tetrahedron, 1), 101u);
  EXPECT_EQ(count(p3.facets, ElementType::Triangle, 3), 84u);
  EXPECT_EQ(count(p1.facets, ElementType::Triangle, 1), 84u);
  EXPECT_EQ(p1.n_nodes(), 45u);
  EXPECT_EQ(p3.n_nodes(), 663u);
  EXPECT_EQ(test::sorted_groups(p3), test::sorted_groups(p1));
  EXPECT_TRUE(p3.x.rowwise().minCoeff().isZero());
  EXPECT_TRUE(p3.x.rowwise().maxCoeff().isOnes());
}

TEST(ReadFixtures, GmshQuadrilaterals) {
  const Mesh m = read_mesh(data("gmsh_quad_41a.msh"));
  EXPECT_EQ(m.dim, 2);
  EXPECT_EQ(count(m.cells, ElementType::Quadrilateral, 1), 73u);
}

TEST(ReadFixtures, MeshioVtuInAsciiRawAndZlibMatchesTheGmshSource) {
  const Mesh gmsh = read_mesh(data("gmsh_tri6_41a.msh"));
  for (const char* name : {"meshio_tri6_ascii.vtu", "meshio_tri6_raw.vtu", "meshio_tri6_zlib.vtu"}) {
    SCOPED_TRACE(name);
    const Mesh m = read_mesh(data(name));
    ASSERT_EQ(m.x.cols(), gmsh.x.cols());
    EXPECT_LT((m.x - gmsh.x).cwiseAbs().maxCoeff(), 1e-11);  // meshio's ASCII has ~12 digits
    ASSERT_EQ(m.cells.size(), 1u);
    EXPECT_EQ(m.cells[0].nodes, gmsh.cells[0].nodes);      // VTK type 22 = Gmsh order at p2
    EXPECT_EQ(m.cells[0].physical, gmsh.cells[0].physical);  // "material" cell array
    EXPECT_EQ(count(m.facets, ElementType::Line, 2), 35u);
  }
}

TEST(ReadFixtures, MeshioMedit) {
  const Mesh m = read_mesh(data("meshio_tet4.mesh"));
  const Mesh gmsh = read_mesh(data("gmsh_tet4_22a.msh"));
  EXPECT_EQ(m.dim, 3);
  EXPECT_LT((m.x - gmsh.x).cwiseAbs().maxCoeff(), 1e-15);
  ASSERT_EQ(m.cells.size(), 1u);
  EXPECT_EQ(m.cells[0].nodes, gmsh.cells[0].nodes);
  EXPECT_EQ(m.cells[0].physical, gmsh.cells[0].physical);
}

// Each cell as its type, order, physical tag and node coordinates (rounded to 1e-12), sorted.
std::vector<std::vector<double>> cells_by_coordinates(const Mesh& m) {
  std::vector<std::vector<double>> cells;
  for (const auto* list : {&m.cells, &m.facets})
    for (const CellBlock& b : *list)
      for (std::size_t c = 0; c < b.n_cells(); ++c) {
        std::vector<double> v{static_cast<double>(b.type), static_cast<double>(b.order), static_cast<double>(b.physical[c])};
        for (int k = 0; k < b.n_nodes_per_cell(); ++k)
          for (Eigen::Index d = 0; d < m.x.rows(); ++d) v.push_back(std::round(m.x(d, b.cell(c)[k]) * 1e12) / 1e12);
        cells.push_back(std::move(v));
      }
  std::sort(cells.begin(), cells.end());
  return cells;
}

// Gmsh's incomplete quadratic cells (serendipity_hybrid.geo, Mesh.SecondOrderIncomplete):
// 15-node prisms, 20-node hexahedra, a 13-node pyramid, 8-node quadrilateral facets, read as
// the complete cells with a node at each quadrilateral face's centre (one per face) and at
// each hexahedron's; the same mesh in the four MSH encodings and from VTK's writer.
TEST(ReadFixtures, GmshIncompleteQuadraticCellsReadAsCompleteOnes) {
  const Mesh m = read_mesh(data("gmsh_serendipity_41a.msh"));
  EXPECT_EQ(m.dim, 3);
  EXPECT_EQ(count(m.cells, ElementType::Prism, 2), 10u);
  EXPECT_EQ(count(m.cells, ElementType::Hexahedron, 2), 2u);
  EXPECT_EQ(count(m.cells, ElementType::Pyramid, 2), 1u);
  EXPECT_EQ(count(m.cells, ElementType::Tetrahedron, 2), 53u);
  EXPECT_EQ(count(m.facets, ElementType::Quadrilateral, 2), 5u);
  EXPECT_EQ(count(m.facets, ElementType::Triangle, 2), 5u);
  EXPECT_EQ(m.n_cells(), 66u);
  // 185 nodes in the file; 29 quadrilateral faces of the prisms, hexahedra and the pyramid
  // (each counted once) and 2 hexahedron centres added.
  EXPECT_EQ(m.n_nodes(), 185u + 29u + 2u);
  EXPECT_EQ(m.node_tags.back(), 216);
  EXPECT_EQ(count_invalid_cells(m), 0u);
  EXPECT_EQ(test::sorted_groups(m), (std::vector<std::tuple<int, int, std::string>>{
                                        {2, 1, "bottom"}, {2, 2, "arc"}, {3, 3, "domain"}}));
  test::expect_meshes_equal(m, read_mesh(data("gmsh_serendipity_41b.msh")), {.tolerance = 1e-15});
  // MSH 2.2 lists the elements by type, tetrahedra first, and VTK's file its points by tag:
  // the same cells, whose nodes come in another order.
  for (const char* other : {"gmsh_serendipity_22a.msh", "gmsh_serendipity_22b.msh", "vtk_serendipity.vtu"}) {
    SCOPED_TRACE(other);
    const Mesh b = read_mesh(data(other));
    EXPECT_EQ(b.n_nodes(), m.n_nodes());
    EXPECT_EQ(cells_by_coordinates(b), cells_by_coordinates(m));
    EXPECT_EQ(test::sorted_groups(b), test::sorted_groups(m));
  }
}

}  // namespace
}  // namespace meshmorph
