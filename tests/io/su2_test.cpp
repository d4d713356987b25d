// SPDX-License-Identifier: MIT
// SU2 .su2: files written by Gmsh 4.8.4 (tests/data/io/gmsh_*.su2: `gmsh -3 cube.geo -format su2`,
// `gmsh -3 ../hybrid_layer.geo -format su2`, `gmsh -2 square_hole.geo -format su2`), round trips
// of every linear type, VTK's wedge order, and what the format cannot hold.
#include "meshmorph/io/su2.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <numeric>
#include <sstream>
#include <string>

#include "io/mesh_compare.h"
#include "meshmorph/error.h"
#include "meshmorph/fem/orientation.h"
#include "meshmorph/fem/structured.h"
#include "meshmorph/io/mesh_io.h"

namespace meshmorph {
namespace {

namespace fs = std::filesystem;

std::string data(const std::string& name) { return std::string(MESHMORPH_TEST_DATA) + "/io/" + name; }

std::size_t count(const Mesh& m, ElementType type) {
  std::size_t n = 0;
  for (const auto* list : {&m.cells, &m.facets})
    for (const CellBlock& b : *list) n += b.type == type ? b.n_cells() : 0;
  return n;
}

// Every cell has a positive volume, and together they fill `volume` (to `tolerance`).
void expect_positive_cells(const Mesh& m, double volume, double tolerance = 1e-12) {
  const std::vector<double> v = signed_volumes(m);
  EXPECT_GT(*std::min_element(v.begin(), v.end()), 0.0);
  EXPECT_NEAR(std::accumulate(v.begin(), v.end(), 0.0), volume, tolerance * volume);
}

std::string su2_text(const Mesh& m) {
  std::ostringstream out;
  write_su2(out, m);
  return out.str();
}

TEST(Su2, GmshTetrahedraWithMarkers) {
  const Mesh m = read_mesh(data("gmsh_tet4.su2"));
  EXPECT_EQ(m.dim, 3);
  ASSERT_EQ(m.cells.size(), 1u);
  EXPECT_EQ(m.cells[0].type, ElementType::Tetrahedron);
  EXPECT_EQ(test::sorted_groups(m),
            (std::vector<std::tuple<int, int, std::string>>{{2, 1, "bottom"}, {2, 2, "sides"}}));
  expect_positive_cells(m, 1.0);
  const auto bottom = m.find_group("bottom");
  ASSERT_TRUE(bottom.has_value());
  for (const std::int32_t j : m.group_nodes(*bottom)) EXPECT_EQ(m.x(2, j), 0.0);
}

TEST(Su2, GmshHybridCellsOfEveryType) {
  const Mesh m = read_mesh(data("gmsh_hybrid.su2"));
  EXPECT_EQ(m.dim, 3);
  EXPECT_EQ(count(m, ElementType::Hexahedron), 12u);  // as OpenFOAM's checkMesh counts them
  EXPECT_EQ(count(m, ElementType::Prism), 42u);
  EXPECT_EQ(count(m, ElementType::Pyramid), 4u);
  EXPECT_EQ(count(m, ElementType::Tetrahedron), 185u);
  expect_positive_cells(m, 2.0);
  // The same mesh in MSH: the same nodes (SU2's ids are Gmsh's tags − 1) and the same cells.
  const Mesh msh = read_mesh(std::string(MESHMORPH_TEST_DATA) + "/hybrid_layer.msh");
  ASSERT_EQ(msh.n_nodes(), m.n_nodes());
  EXPECT_EQ((msh.x - m.x).cwiseAbs().maxCoeff(), 0.0);
  for (const CellBlock& b : msh.cells) {
    const auto same =
        std::find_if(m.cells.begin(), m.cells.end(), [&](const CellBlock& c) { return c.type == b.type; });
    ASSERT_NE(same, m.cells.end());
    EXPECT_EQ(same->nodes, b.nodes) << name_of(b.type);
  }
}

TEST(Su2, GmshTrianglesIn2D) {
  const Mesh m = read_mesh(data("gmsh_tri3.su2"));
  EXPECT_EQ(m.dim, 2);
  EXPECT_EQ(m.x.rows(), 2);
  EXPECT_EQ(test::sorted_groups(m),
            (std::vector<std::tuple<int, int, std::string>>{{1, 1, "hole_wall"}, {1, 2, "outer"}}));
  expect_positive_cells(m, 2.0 - 0.2 * 0.2 * 3.14159265358979, 0.01);  // the hole is a polygon of 7 sides
}

// VTK_WEDGE (13) lists its base triangle facing away from the top: Gmsh's (0 1 2 3 4 5) is
// VTK's (0 2 1 3 5 4). Gmsh wrote this prism as "13 1 0 6 4 3 7" beside its MSH "2 7 1 5 8 4".
TEST(Su2, WedgeIsVtkOrdered) {
  const std::string text =
      "NDIME= 3\nNELEM= 1\n13 1 0 6 4 3 7 0\nNPOIN= 8\n0 0 0 0\n1 0 0 1\n0 1 0 2\n0 0 1 3\n1 0 1 4\n0 1 1 5\n"
      "0.5 0.5 0 6\n0.5 0.5 1 7\nNMARK= 0\n";
  const Mesh m = parse_su2(text, "wedge.su2");
  ASSERT_EQ(m.cells.size(), 1u);
  EXPECT_EQ(m.cells[0].nodes, (std::vector<std::int32_t>{1, 6, 0, 4, 7, 3}));
  expect_positive_cells(m, 0.25);
  EXPECT_NE(su2_text(m).find("\n13 1 0 6 4 3 7 0\n"), std::string::npos);
}

// Our own files read back to the same mesh and write again byte for byte, for every linear type.
TEST(Su2, RoundTripEveryLinearType) {
  for (const ElementType type : {ElementType::Triangle, ElementType::Quadrilateral, ElementType::Tetrahedron,
                                 ElementType::Hexahedron, ElementType::Prism, ElementType::Pyramid}) {
    SCOPED_TRACE(name_of(type));
    Mesh m = structured_mesh(type, 1, 2);
    m.x += 1e-3 * Eigen::MatrixXd::Random(m.x.rows(), m.x.cols());  // coordinates of 17 digits
    const std::string first = su2_text(m);
    const Mesh back = parse_su2(first, "first.su2");
    EXPECT_EQ((back.x - m.x).cwiseAbs().maxCoeff(), 0.0);
    ASSERT_EQ(back.cells.size(), m.cells.size());
    for (std::size_t b = 0; b < m.cells.size(); ++b) EXPECT_EQ(back.cells[b].nodes, m.cells[b].nodes);
    for (const PhysicalGroup& g : m.groups) {
      if (g.dim != m.dim - 1) continue;
      const auto same = back.find_group(g.name);
      ASSERT_TRUE(same.has_value()) << g.name;
      EXPECT_EQ(back.group_nodes(*same), m.group_nodes(g)) << g.name;
    }
    EXPECT_EQ(su2_text(back), first);
  }
}

TEST(Su2, WriteMeshByExtensionAndReadBack) {
  const fs::path file = fs::temp_directory_path() / ("meshmorph_su2_" + std::to_string(::getpid()) + ".su2");
  const Mesh m = structured_mesh(ElementType::Hexahedron, 1, 2);
  write_mesh(file, m);
  const Mesh back = read_mesh(file);
  EXPECT_EQ(back.n_cells(), m.n_cells());
  EXPECT_EQ(back.groups.size(), 6u);  // the facet groups; the cells' "domain" has no place in SU2
  fs::remove(file);
}

TEST(Su2, CurvedCellsAndMarkerNamesWithSpacesAreRefused) {
  EXPECT_THROW(su2_text(structured_mesh(ElementType::Triangle, 2, 1)), InputError);
  try {
    su2_text(structured_mesh(ElementType::Quadrilateral, 2, 1));
    ADD_FAILURE() << "no exception";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("SU2 .su2 holds linear cells only"), std::string::npos) << e.what();
  }
  Mesh m = structured_mesh(ElementType::Triangle, 1, 1);
  m.groups[1].name = "left wall";
  EXPECT_THROW(su2_text(m), InputError);
}

TEST(Su2, OptionalIndicesCommentsAndAnyOrderOfSections) {
  const std::string text =
      "% a comment\nNDIME=2\nNPOIN= 4 4\n0 0\n1 0\n1 1\n0 1\nNMARK= 1\nMARKER_TAG= wall\nMARKER_ELEMS= 1\n3 0 1\n"
      "NELEM= 2\n5 0 1 2\n5 0 2 3 1\n";
  const Mesh m = parse_su2(text, "any_order.su2");
  EXPECT_EQ(m.n_cells(), 2u);
  EXPECT_EQ(m.n_nodes(), 4u);
  EXPECT_EQ(count(m, ElementType::Line), 1u);
}

// Every prefix of a file is an InputError naming its line, or (a cut before NMARK, whose
// section is optional) a mesh without markers: never a crash.
TEST(Su2, EveryTruncationIsAnInputErrorOrAMeshWithoutMarkers) {
  const std::string full = su2_text(structured_mesh(ElementType::Prism, 1, 1));
  int errors = 0;
  for (std::size_t n = 0; n < full.size(); ++n) {
    try {
      parse_su2(full.substr(0, n), "cut.su2");
      EXPECT_LT(full.find("NMARK"), n + 10) << n;
    } catch (const InputError& e) {
      ++errors;
      EXPECT_EQ(std::string(e.what()).rfind("cut.su2: line ", 0), 0u) << e.what();
    }
  }
  EXPECT_GT(errors, static_cast<int>(full.size()) / 2);
}

}  // namespace
}  // namespace meshmorph
