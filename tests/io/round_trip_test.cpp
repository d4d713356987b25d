// SPDX-License-Identifier: MIT
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
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
  const fs::path dir = fs::temp_directory_path() / ("meshmorph_io_test_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir / name;
}

Mesh round_trip(const Mesh& m, const std::string& name, MeshFormat format, bool binary) {
  const fs::path p = scratch(name);
  WriteOptions opt;
  opt.format = format;
  opt.binary = binary;
  write_mesh(p, m, opt);
  Mesh r = read_mesh(p);
  fs::remove(p);
  return r;
}

using Case = std::tuple<ElementType, int, bool>;  // type, order, binary

class MeshRoundTrip : public ::testing::TestWithParam<Case> {};

// MSH 4.1 → internal → MSH 2.2 → VTU → internal keeps coordinates, connectivity, tags and
// groups bit for bit, in binary and in ASCII (shortest exact doubles).
TEST_P(MeshRoundTrip, Msh41ThenMsh22ThenVtuKeepEverything) {
  const auto [type, order, binary] = GetParam();
  Mesh m0 = structured_mesh(type, order, 2);
  // Make the coordinates non-trivial doubles so that printing precision matters.
  for (Eigen::Index j = 0; j < m0.x.cols(); ++j)
    for (Eigen::Index k = 0; k < m0.x.rows(); ++k) m0.x(k, j) = m0.x(k, j) / 3.0 + 0.1 * std::sin(1.0 + static_cast<double>(j + k));
  // Node fields: VTU PointData and MSH $NodeData, bit for bit, non-finite values included.
  const Eigen::Index n = m0.x.cols();
  m0.node_fields["phi"] = Eigen::VectorXd::LinSpaced(n, 0, 1).array().sin() / 7.0;
  Eigen::VectorXd special = Eigen::VectorXd::Constant(n, 1e300);
  special(0) = std::numeric_limits<double>::quiet_NaN();
  special(1) = -std::numeric_limits<double>::infinity();
  special(2) = std::numeric_limits<double>::denorm_min();
  m0.node_fields["special value"] = special;
  const std::string tag = std::string(name_of(type)) + std::to_string(order) + (binary ? "b" : "a");
  const Mesh m1 = round_trip(m0, tag + ".msh", MeshFormat::Msh41, binary);
  {
    SCOPED_TRACE("MSH 4.1");
    test::expect_meshes_equal(m0, m1, {.node_tags = true, .entities = false});
  }
  const Mesh m2 = round_trip(m1, tag + "_22.msh", MeshFormat::Msh22, binary);
  {
    SCOPED_TRACE("MSH 2.2");
    test::expect_meshes_equal(m1, m2);
  }
  const Mesh m3 = round_trip(m2, tag + ".vtu", MeshFormat::Vtu, binary);
  {
    SCOPED_TRACE("VTU");
    test::expect_meshes_equal(m2, m3);
  }
  const Mesh m4 = round_trip(m3, tag + "_again.msh", MeshFormat::Msh41, binary);
  {
    SCOPED_TRACE("MSH 4.1 again");
    test::expect_meshes_equal(m3, m4);
  }
}

std::vector<Case> all_cases() {
  std::vector<Case> cases;
  for (const ElementType t : {ElementType::Triangle, ElementType::Quadrilateral, ElementType::Tetrahedron, ElementType::Hexahedron,
                              ElementType::Prism, ElementType::Pyramid})
    for (int p = 1; p <= (t == ElementType::Pyramid ? 1 : max_order_of(t)); ++p)  // (P2 pyramids: no VTU)
      for (const bool binary : {false, true}) cases.emplace_back(t, p, binary);
  return cases;
}

INSTANTIATE_TEST_SUITE_P(AllTypesAndOrders, MeshRoundTrip, ::testing::ValuesIn(all_cases()),
                         [](const ::testing::TestParamInfo<Case>& param) {
                           return std::string(name_of(std::get<0>(param.param))) + "P" +
                                  std::to_string(std::get<1>(param.param)) + (std::get<2>(param.param) ? "Binary" : "Ascii");
                         });

TEST(MeshRoundTrip, SparseUnorderedNodeTagsSurviveMsh) {
  Mesh m = structured_mesh(ElementType::Tetrahedron, 2, 2);
  const auto n = static_cast<std::int64_t>(m.n_nodes());
  for (std::int64_t i = 0; i < n; ++i) m.node_tags[static_cast<std::size_t>(i)] = 1000000 + 7 * (n - i);
  // $NodeData records are matched to the nodes through their tags.
  m.node_fields["phi"] = m.x.row(0).transpose() + 0.5 * m.x.row(2).transpose();
  for (const auto format : {MeshFormat::Msh41, MeshFormat::Msh22})
    for (const bool binary : {false, true}) {
      SCOPED_TRACE(std::string(format == MeshFormat::Msh41 ? "4.1" : "2.2") + (binary ? " binary" : " ascii"));
      const Mesh r = round_trip(m, "sparse.msh", format, binary);
      test::expect_meshes_equal(m, r, {.node_tags = true, .entities = false});
    }
}

TEST(MeshRoundTrip, MeditKeepsLinearCellsAndReferences) {
  for (const ElementType t : {ElementType::Triangle, ElementType::Quadrilateral, ElementType::Tetrahedron, ElementType::Hexahedron}) {
    SCOPED_TRACE(std::string(name_of(t)));
    Mesh m = structured_mesh(t, 1, 2);
    m.node_fields["phi"] = Eigen::VectorXd::Ones(m.x.cols());
    const Mesh r = round_trip(m, "linear.mesh", MeshFormat::Medit, false);
    EXPECT_TRUE(r.node_fields.empty());  // Medit has no node data
    EXPECT_TRUE(m.x == r.x);
    ASSERT_EQ(r.cells.size(), 1u);
    EXPECT_EQ(r.cells[0].nodes, m.cells[0].nodes);
    EXPECT_EQ(r.cells[0].physical, m.cells[0].physical);
    ASSERT_EQ(r.facets.size(), m.facets.size());
    EXPECT_EQ(r.facets[0].nodes, m.facets[0].nodes);
    EXPECT_EQ(r.facets[0].physical, m.facets[0].physical);
    // Medit has no group names: the groups come back by number.
    EXPECT_EQ(r.groups.size(), m.groups.size());
  }
}

// Hexahedron, pyramid, tetrahedron and prism in one mesh, with triangles and quadrilaterals in
// one boundary group: every format keeps it bit for bit (Medit: cells, facets and references).
TEST(MeshRoundTrip, MixedCellsInEveryFormat) {
  Mesh m = test::mixed_cells_mesh();
  m.x.row(1) = m.x.row(1) / 3.0;
  for (const auto format : {MeshFormat::Msh41, MeshFormat::Msh22, MeshFormat::Vtu})
    for (const bool binary : {false, true}) {
      SCOPED_TRACE(std::to_string(static_cast<int>(format)) + (binary ? " binary" : " ascii"));
      const Mesh r = round_trip(m, format == MeshFormat::Vtu ? "mixed.vtu" : "mixed.msh", format, binary);
      test::expect_meshes_equal(m, r);
    }
  const Mesh r = round_trip(m, "mixed.mesh", MeshFormat::Medit, false);
  EXPECT_TRUE(m.x == r.x);
  ASSERT_EQ(r.cells.size(), m.cells.size());
  for (const ElementType t : {ElementType::Hexahedron, ElementType::Pyramid, ElementType::Tetrahedron, ElementType::Prism}) {
    const auto same = [&](const CellBlock& b) { return b.type == t; };
    const auto a = std::find_if(m.cells.cbegin(), m.cells.cend(), same);
    const auto b = std::find_if(r.cells.cbegin(), r.cells.cend(), same);
    ASSERT_TRUE(b != r.cells.end()) << name_of(t);
    EXPECT_EQ(a->nodes, b->nodes) << name_of(t);
  }
  ASSERT_EQ(r.facets.size(), 2u);
  for (std::size_t f = 0; f < 2; ++f) EXPECT_EQ(r.facets[f].nodes, m.facets[f].nodes);
}

// P2 pyramids: MSH 4.1 and 2.2 bit for bit; VTU refuses them (VTK 9.1 has no cell class for
// them) and leaves no file.
TEST(MeshRoundTrip, QuadraticPyramidsInMshNotVtu) {
  Mesh m = structured_mesh(ElementType::Pyramid, 2, 2);
  m.x = m.x / 3.0;
  for (const auto format : {MeshFormat::Msh41, MeshFormat::Msh22})
    for (const bool binary : {false, true})
      test::expect_meshes_equal(m, round_trip(m, "pyramid2.msh", format, binary), {.node_tags = true, .entities = false});
  const fs::path p = scratch("pyramid2.vtu");
  EXPECT_THROW(write_mesh(p, m), InputError);
  EXPECT_FALSE(fs::exists(p));
}

TEST(MeshRoundTrip, MeditRejectsCurvedCellsAndLeavesNoFile) {
  const Mesh m = structured_mesh(ElementType::Triangle, 2, 1);
  const fs::path p = scratch("curved.mesh");
  EXPECT_THROW(write_mesh(p, m), InputError);
  EXPECT_FALSE(fs::exists(p));
}

TEST(MeshRoundTrip, VtuCellDataHasOneValuePerCell) {
  const Mesh m = structured_mesh(ElementType::Quadrilateral, 1, 2);
  WriteOptions opt;
  opt.cell_data["quality"] = std::vector<double>(m.n_cells(), 0.5);
  const fs::path p = scratch("cd.vtu");
  write_mesh(p, m, opt);
  const Mesh r = read_mesh(p);
  test::expect_meshes_equal(m, r, {.node_tags = true, .entities = false});
  opt.cell_data["quality"].pop_back();
  EXPECT_THROW(write_mesh(p, m, opt), std::invalid_argument);
}

}  // namespace
}  // namespace meshmorph
