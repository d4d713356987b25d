// SPDX-License-Identifier: MIT
// MSH → CGNS → Exodus II → VTU → internal: coordinates, connectivity and groups identical
// for every family and order each format holds; what they cannot hold is refused.
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <numeric>
#include <string>
#include <tuple>

#include <gtest/gtest.h>

#include "io/mesh_compare.h"
#include "meshmorph/error.h"
#include "meshmorph/fem/structured.h"
#include "meshmorph/io/mesh_io.h"
#include "support/mixed_mesh.h"

namespace meshmorph {
namespace {

namespace fs = std::filesystem;

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("meshmorph_solver_io_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir / name;
}

Mesh through(const Mesh& m, const std::string& name) {
  const fs::path p = scratch(name);
  write_mesh(p, m);
  Mesh r = read_mesh(p);
  fs::remove(p);
  return r;
}

// Exodus side sets hold a group each: facets come back group by group, their blocks in the
// order the side sets meet them. The same facets in a canonical order: blocks by family, each
// by group, then as they were.
Mesh facets_by_group(Mesh m) {
  std::stable_sort(m.facets.begin(), m.facets.end(), [](const CellBlock& a, const CellBlock& b) { return a.type < b.type; });
  for (CellBlock& b : m.facets) {
    std::vector<std::size_t> order(b.n_cells());
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) { return b.physical[i] < b.physical[j]; });
    CellBlock sorted{b.type, b.order, {}, {}, {}};
    for (const std::size_t c : order) sorted.push_back(b.cell(c), b.physical[c], b.entity[c]);
    b = std::move(sorted);
  }
  return m;
}

constexpr test::CompareOptions k_exact{.node_tags = true, .entities = false, .node_fields = false};

using Case = std::tuple<ElementType, int>;
class SolverFormatsRoundTrip : public ::testing::TestWithParam<Case> {};

TEST_P(SolverFormatsRoundTrip, KeepsEverything) {
  const auto [type, order] = GetParam();
  Mesh m0 = structured_mesh(type, order, 2);
  for (Eigen::Index j = 0; j < m0.x.cols(); ++j)
    for (Eigen::Index k = 0; k < m0.x.rows(); ++k) m0.x(k, j) = m0.x(k, j) / 3.0 + 0.01 * std::sin(1.0 + static_cast<double>(j + k));
  const std::string tag = std::string(name_of(type)) + std::to_string(order);
  const Mesh m1 = through(m0, tag + ".msh");
  const Mesh m2 = through(m1, tag + ".cgns");
  {
    SCOPED_TRACE("CGNS");
    test::expect_meshes_equal(m1, m2, k_exact);
  }
  if (order > 2) {  // Exodus II holds orders 1 and 2: refused, and nothing is written
    const fs::path p = scratch(tag + ".exo");
    EXPECT_THROW(write_mesh(p, m2), InputError);
    EXPECT_FALSE(fs::exists(p));
    return;
  }
  const Mesh m3 = through(m2, tag + ".exo");
  {
    SCOPED_TRACE("Exodus II");
    test::expect_meshes_equal(facets_by_group(m2), facets_by_group(m3), k_exact);
  }
  if (type == ElementType::Pyramid && order == 2) return;  // (no P2 pyramids in VTU)
  const Mesh m4 = through(m3, tag + ".vtu");
  SCOPED_TRACE("VTU");
  test::expect_meshes_equal(m3, m4, k_exact);
}

std::vector<Case> all_cases() {
  std::vector<Case> cases;
  for (const ElementType t : {ElementType::Triangle, ElementType::Quadrilateral, ElementType::Tetrahedron, ElementType::Hexahedron,
                              ElementType::Prism, ElementType::Pyramid})
    for (int p = 1; p <= max_order_of(t); ++p) cases.emplace_back(t, p);
  return cases;
}

INSTANTIATE_TEST_SUITE_P(AllTypesAndOrders, SolverFormatsRoundTrip, ::testing::ValuesIn(all_cases()),
                         [](const ::testing::TestParamInfo<Case>& param) {
                           return std::string(name_of(std::get<0>(param.param))) + "P" + std::to_string(std::get<1>(param.param));
                         });

// Four families in one mesh, one boundary group of triangles and quadrilaterals.
TEST(SolverFormatsRoundTrip, MixedCells) {
  const Mesh m = test::mixed_cells_mesh();
  for (const char* name : {"mixed.cgns", "mixed.e", "mixed.ex2"}) {
    SCOPED_TRACE(name);
    test::expect_meshes_equal(m, through(m, name), {.node_tags = true, .entities = false});
  }
}

// Cells of several groups in one block come back grouped, each group its own section or
// element block; unnamed groups stay unnamed; point groups are node sets / Vertex regions.
TEST(SolverFormatsRoundTrip, GroupsOfCellsPointsAndUnnamedTags) {
  Mesh m = structured_mesh(ElementType::Triangle, 2, 2);
  CellBlock& cells = m.cells[0];
  for (std::size_t c = 0; c < cells.n_cells(); ++c) cells.physical[c] = c < cells.n_cells() / 2 ? 1 : 7;
  CellBlock points{ElementType::Point, 1, {}, {}, {}};
  const std::int32_t corner = 0, other = 3;
  points.push_back(&corner, 5);
  points.push_back(&other, 5);
  m.facets.push_back(points);
  m.groups.push_back({0, 5, "corner"});  // tag 7 of dimension 2 stays unnamed
  for (const char* name : {"groups.cgns", "groups.exo"}) {
    SCOPED_TRACE(name);
    const Mesh r = through(m, name);
    EXPECT_EQ(test::sorted_groups(r), test::sorted_groups(through(m, "groups.msh")));
    ASSERT_EQ(r.cells.size(), 1u);
    EXPECT_EQ(r.cells[0].physical, cells.physical);  // the first half is tag 1 already
    EXPECT_EQ(r.cells[0].nodes, cells.nodes);
    const auto pts = std::find_if(r.facets.begin(), r.facets.end(), [](const CellBlock& b) { return b.type == ElementType::Point; });
    ASSERT_NE(pts, r.facets.end());
    EXPECT_EQ(pts->nodes, points.nodes);
  }
}

TEST(SolverFormatsRoundTrip, NamesTheFormatsCannotHold) {
  Mesh m = structured_mesh(ElementType::Quadrilateral, 1, 1);
  m.groups[1].name = std::string(33, 'a');
  for (const char* name : {"long.cgns", "long.exo"}) {
    SCOPED_TRACE(name);
    const fs::path p = scratch(name);
    try {
      write_mesh(p, m);
      ADD_FAILURE() << "no exception";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(p.string() + ": group name 'aaa"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("32 characters"), std::string::npos) << e.what();
    }
    EXPECT_FALSE(fs::exists(p));
  }
  m.groups[1].name = "a/b";
  EXPECT_THROW(write_mesh(scratch("slash.cgns"), m), InputError);
}

}  // namespace
}  // namespace meshmorph
