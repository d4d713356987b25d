// SPDX-License-Identifier: MIT
#include "meshmorph/io/vtk_ordering.h"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <tuple>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <pugixml.hpp>

#include "meshmorph/fem/reference_element.h"
#include "meshmorph/io/mesh_io.h"

namespace meshmorph {
namespace {

namespace fs = std::filesystem;

ElementType family(const std::string& name) {
  if (name == "triangle") return ElementType::Triangle;
  if (name == "quadrilateral") return ElementType::Quadrilateral;
  if (name == "tetrahedron") return ElementType::Tetrahedron;
  return ElementType::Hexahedron;
}

// Reference coordinates of the Gmsh nodes mapped to VTK's parametric domain ([0,1]^d).
Eigen::MatrixXd gmsh_nodes_in_vtk_domain(ElementType type, int order) {
  Eigen::MatrixXd x = reference_element(type, order).nodes;
  if (!is_simplex(type)) x = (x.array() + 1.0) / 2.0;
  return x;
}

// Permutations measured with Gmsh 4.8.4 and VTK 9.1.0 on this machine (shared/reference).
TEST(VtkOrdering, PermutationsMatchGmshAndVtkReferenceData) {
  std::ifstream in(std::string(MESHMORPH_TEST_DATA) + "/io/gmsh_vtk_node_permutations.json");
  ASSERT_TRUE(in) << "missing tests/data/io/gmsh_vtk_node_permutations.json";
  const nlohmann::json data = nlohmann::json::parse(in);
  int checked = 0;
  for (const auto& [key, cell] : data.at("cells").items()) {
    SCOPED_TRACE(key);
    const std::size_t sep = key.find("_p");
    const ElementType type = family(key.substr(0, sep));
    const int order = std::stoi(key.substr(sep + 2));
    EXPECT_EQ(vtk_cell_type(type), cell.at("vtk_type").get<int>());
    const auto expected = cell.at("vtk_index_to_gmsh_index").get<std::vector<int>>();
    EXPECT_EQ(vtk_to_gmsh_permutation(type, order), expected);
    // The internal reference element is Gmsh's: same coordinates in the same order.
    const auto gmsh = cell.at("gmsh_ref_coords").get<std::vector<std::vector<double>>>();
    const Eigen::MatrixXd& nodes = reference_element(type, order).nodes;
    ASSERT_EQ(static_cast<std::size_t>(nodes.cols()), gmsh.size());
    for (std::size_t i = 0; i < gmsh.size(); ++i)
      for (std::size_t k = 0; k < gmsh[i].size(); ++k)
        EXPECT_NEAR(nodes(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(i)), gmsh[i][k], 1e-12);
    ++checked;
  }
  EXPECT_EQ(checked, 16);
}

TEST(VtkOrdering, ParametricPointsOfLinearCellsAreVtkCorners) {
  const Eigen::MatrixXd hex = vtk_lagrange_points(ElementType::Hexahedron, 1);
  Eigen::MatrixXd expected(3, 8);
  expected << 0, 1, 1, 0, 0, 1, 1, 0,  //
      0, 0, 1, 1, 0, 0, 1, 1,          //
      0, 0, 0, 0, 1, 1, 1, 1;
  EXPECT_TRUE(hex == expected);
  EXPECT_EQ(vtk_lagrange_points(ElementType::Line, 3).cols(), 4);
  EXPECT_DOUBLE_EQ(vtk_lagrange_points(ElementType::Line, 3)(0, 2), 1.0 / 3.0);
}

// One cell whose node i (internal order) sits at the i-th Gmsh reference point: in the
// written .vtu, the point of the cell's i-th VTK node is VTK's i-th parametric point, and
// reading the file back puts every node where it was.
TEST(VtkOrdering, WrittenCellNodesSitAtVtkParametricPoints) {
  const fs::path dir = fs::temp_directory_path() / ("meshmorph_vtk_order_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  for (const ElementType type : {ElementType::Triangle, ElementType::Quadrilateral, ElementType::Tetrahedron, ElementType::Hexahedron})
    for (int order = 1; order <= max_order_of(type); ++order)
      for (const bool binary : {false, true}) {
        SCOPED_TRACE(std::string(name_of(type)) + " order " + std::to_string(order) + (binary ? " binary" : " ascii"));
        const Eigen::MatrixXd ref = gmsh_nodes_in_vtk_domain(type, order);
        Mesh m;
        m.dim = topological_dim(type);
        m.x = ref;
        for (Eigen::Index i = 0; i < ref.cols(); ++i) m.node_tags.push_back(i + 1);
        CellBlock b;
        b.type = type;
        b.order = order;
        for (Eigen::Index i = 0; i < ref.cols(); ++i) b.nodes.push_back(static_cast<std::int32_t>(i));
        b.physical = {1};
        b.entity = {1};
        m.cells.push_back(b);
        const fs::path p = dir / "cell.vtu";
        WriteOptions opt;
        opt.binary = binary;
        write_mesh(p, m, opt);

        const Mesh r = read_mesh(p);
        ASSERT_EQ(r.cells.size(), 1u);
        EXPECT_TRUE(r.x == m.x);
        EXPECT_EQ(r.cells[0].nodes, b.nodes);
        if (binary) continue;
        // In the ASCII file: connectivity[i] is a point at VTK's i-th parametric coordinate.
        pugi::xml_document doc;
        ASSERT_TRUE(doc.load_file(p.c_str()));
        const auto piece = doc.child("VTKFile").child("UnstructuredGrid").child("Piece");
        std::istringstream pts(piece.child("Points").child("DataArray").text().get());
        std::vector<double> xyz{std::istream_iterator<double>(pts), std::istream_iterator<double>()};
        std::istringstream conn_text(piece.child("Cells").find_child_by_attribute("Name", "connectivity").text().get());
        std::vector<int> conn{std::istream_iterator<int>(conn_text), std::istream_iterator<int>()};
        const Eigen::MatrixXd vtk = vtk_lagrange_points(type, order);
        ASSERT_EQ(conn.size(), static_cast<std::size_t>(vtk.cols()));
        for (std::size_t i = 0; i < conn.size(); ++i)
          for (Eigen::Index k = 0; k < vtk.rows(); ++k)
            EXPECT_NEAR(xyz[3 * static_cast<std::size_t>(conn[i]) + static_cast<std::size_t>(k)], vtk(k, static_cast<Eigen::Index>(i)), 1e-14)
                << "VTK node " << i;
      }
  fs::remove_all(dir);
}

// A file of VTKFile version below 2.1 holds Lagrange hexahedra in VTK 8's numbering: edges
// 10 and 11 swapped. Our own file (version 2.2), rewritten that way, reads back the same.
TEST(VtkOrdering, Vtk8HexahedraAreRenumbered) {
  const fs::path dir = fs::temp_directory_path() / ("meshmorph_vtk8_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  for (int order = 2; order <= 3; ++order) {
    SCOPED_TRACE("order " + std::to_string(order));
    Mesh m;
    m.dim = 3;
    m.x = gmsh_nodes_in_vtk_domain(ElementType::Hexahedron, order);
    for (Eigen::Index i = 0; i < m.x.cols(); ++i) m.node_tags.push_back(i + 1);
    CellBlock b;
    b.type = ElementType::Hexahedron;
    b.order = order;
    for (Eigen::Index i = 0; i < m.x.cols(); ++i) b.nodes.push_back(static_cast<std::int32_t>(i));
    b.physical = {1};
    b.entity = {1};
    m.cells.push_back(b);
    write_mesh(dir / "v9.vtu", m);
    pugi::xml_document doc;
    ASSERT_TRUE(doc.load_file((dir / "v9.vtu").c_str()));
    ASSERT_STREQ(doc.child("VTKFile").attribute("version").as_string(), "2.2");
    auto conn_node = doc.child("VTKFile").child("UnstructuredGrid").child("Piece").child("Cells").find_child_by_attribute(
        "Name", "connectivity");
    std::istringstream conn_text(conn_node.text().get());
    std::vector<int> conn{std::istream_iterator<int>(conn_text), std::istream_iterator<int>()};
    const int e = order - 1, first = 8 + 10 * e;
    std::swap_ranges(conn.begin() + first, conn.begin() + first + e, conn.begin() + first + e);
    std::ostringstream v8;
    for (int v : conn) v8 << v << ' ';
    conn_node.text().set(v8.str().c_str());
    doc.child("VTKFile").attribute("version").set_value("1.0");
    ASSERT_TRUE(doc.save_file((dir / "v8.vtu").c_str()));
    EXPECT_EQ(read_mesh(dir / "v8.vtu").cells[0].nodes, b.nodes);
    doc.child("VTKFile").attribute("version").set_value("2.1");  // VTK 9's numbering from 2.1 on
    ASSERT_TRUE(doc.save_file((dir / "v8_as_v9.vtu").c_str()));
    EXPECT_NE(read_mesh(dir / "v8_as_v9.vtu").cells[0].nodes, b.nodes);
  }
  fs::remove_all(dir);
}


// Prisms and pyramids: the internal reference nodes are Gmsh's (types 6, 13 and 7 as Gmsh
// 4.8.4's getElementProperties gives them); VTK's classic wedge is Gmsh's prism with its base
// and top triangles numbered the other way round, VTK's Lagrange wedge and pyramid are Gmsh's
// orientation, and the P2 wedge's nodes lie where VTK 9.1's vtkLagrangeWedge puts them.
TEST(VtkOrdering, PrismAndPyramidFollowGmshAndVtk) {
  std::ifstream in(std::string(MESHMORPH_TEST_DATA) + "/io/gmsh_prism_pyramid_reference.json");
  ASSERT_TRUE(in) << "missing tests/data/io/gmsh_prism_pyramid_reference.json";
  const nlohmann::json data = nlohmann::json::parse(in);
  for (const auto& [code, type, order] : {std::tuple{"6", ElementType::Prism, 1}, std::tuple{"13", ElementType::Prism, 2},
                                          std::tuple{"7", ElementType::Pyramid, 1}}) {
    SCOPED_TRACE(code);
    const auto gmsh = data.at("cells").at(code).at("gmsh_ref_coords").get<std::vector<std::vector<double>>>();
    const Eigen::MatrixXd& nodes = reference_element(type, order).nodes;
    ASSERT_EQ(static_cast<std::size_t>(nodes.cols()), gmsh.size());
    for (std::size_t i = 0; i < gmsh.size(); ++i)
      for (std::size_t k = 0; k < 3; ++k) EXPECT_EQ(nodes(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(i)), gmsh[i][k]);
  }
  EXPECT_EQ(vtk_cell_permutation(13, ElementType::Prism, 1), (std::vector<int>{0, 2, 1, 3, 5, 4}));
  EXPECT_EQ(vtk_cell_permutation(73, ElementType::Prism, 1), (std::vector<int>{0, 1, 2, 3, 4, 5}));
  EXPECT_EQ(vtk_cell_permutation(14, ElementType::Pyramid, 1), (std::vector<int>{0, 1, 2, 3, 4}));
  // VTK 9.1's vtkLagrangeWedge parametric coordinates of order 2 (GetParametricCoords).
  const std::vector<std::array<double, 3>> lagrange_wedge{
      {0, 0, 0},    {1, 0, 0},    {0, 1, 0},   {0, 0, 1},    {1, 0, 1},    {0, 1, 1},
      {.5, 0, 0},   {.5, .5, 0},  {0, .5, 0},  {.5, 0, 1},   {.5, .5, 1},  {0, .5, 1},
      {0, 0, .5},   {1, 0, .5},   {0, 1, .5},  {.5, 0, .5},  {.5, .5, .5}, {0, .5, .5}};
  const Eigen::MatrixXd vtk = vtk_lagrange_points(ElementType::Prism, 2);
  const Eigen::MatrixXd& gmsh = reference_element(ElementType::Prism, 2).nodes;
  const auto& perm = vtk_to_gmsh_permutation(ElementType::Prism, 2);
  for (int i = 0; i < 18; ++i) {
    const auto& v = lagrange_wedge[static_cast<std::size_t>(i)];
    EXPECT_EQ(Eigen::Vector3d(vtk.col(i)), Eigen::Vector3d(v[0], v[1], v[2])) << i;
    const Eigen::Vector3d g = gmsh.col(perm[static_cast<std::size_t>(i)]);
    EXPECT_EQ(Eigen::Vector3d(g(0), g(1), (g(2) + 1) / 2), Eigen::Vector3d(vtk.col(i))) << i;
  }
}

// Prisms of orders 3 and 4 (Gmsh 90 and 91): the reference nodes sit where the prism that Gmsh
// 4.8.4 meshes of the reference prism puts them (tests/data/io), and each VTK node where VTK
// 9.1's vtkLagrangeWedge of that order puts its parametric point (GetParametricCoords × p).
TEST(VtkOrdering, CubicAndQuarticPrismsFollowGmshAndVtk) {
  std::ifstream in(std::string(MESHMORPH_TEST_DATA) + "/io/gmsh_prism_pyramid_reference.json");
  ASSERT_TRUE(in);
  const nlohmann::json data = nlohmann::json::parse(in);
  for (const auto& [code, order] : {std::pair{"90", 3}, std::pair{"91", 4}}) {
    SCOPED_TRACE(code);
    const auto gmsh = data.at("cells").at(code).at("gmsh_ref_coords").get<std::vector<std::vector<double>>>();
    const Eigen::MatrixXd& nodes = reference_element(ElementType::Prism, order).nodes;
    ASSERT_EQ(static_cast<std::size_t>(nodes.cols()), gmsh.size());
    for (std::size_t i = 0; i < gmsh.size(); ++i)
      for (std::size_t k = 0; k < 3; ++k) EXPECT_NEAR(nodes(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(i)), gmsh[i][k], 1e-10) << i;
  }
  const std::vector<std::vector<std::array<int, 3>>> vtk_wedges{
      {{0, 0, 0}, {3, 0, 0}, {0, 3, 0}, {0, 0, 3}, {3, 0, 3}, {0, 3, 3}, {1, 0, 0}, {2, 0, 0}, {2, 1, 0},
       {1, 2, 0}, {0, 2, 0}, {0, 1, 0}, {1, 0, 3}, {2, 0, 3}, {2, 1, 3}, {1, 2, 3}, {0, 2, 3}, {0, 1, 3},
       {0, 0, 1}, {0, 0, 2}, {3, 0, 1}, {3, 0, 2}, {0, 3, 1}, {0, 3, 2}, {1, 1, 0}, {1, 1, 3}, {1, 0, 1},
       {2, 0, 1}, {1, 0, 2}, {2, 0, 2}, {2, 1, 1}, {1, 2, 1}, {2, 1, 2}, {1, 2, 2}, {0, 2, 1}, {0, 1, 1},
       {0, 2, 2}, {0, 1, 2}, {1, 1, 1}, {1, 1, 2}},
      {{0, 0, 0}, {4, 0, 0}, {0, 4, 0}, {0, 0, 4}, {4, 0, 4}, {0, 4, 4}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0},
       {3, 1, 0}, {2, 2, 0}, {1, 3, 0}, {0, 3, 0}, {0, 2, 0}, {0, 1, 0}, {1, 0, 4}, {2, 0, 4}, {3, 0, 4},
       {3, 1, 4}, {2, 2, 4}, {1, 3, 4}, {0, 3, 4}, {0, 2, 4}, {0, 1, 4}, {0, 0, 1}, {0, 0, 2}, {0, 0, 3},
       {4, 0, 1}, {4, 0, 2}, {4, 0, 3}, {0, 4, 1}, {0, 4, 2}, {0, 4, 3}, {1, 1, 0}, {2, 1, 0}, {1, 2, 0},
       {1, 1, 4}, {2, 1, 4}, {1, 2, 4}, {1, 0, 1}, {2, 0, 1}, {3, 0, 1}, {1, 0, 2}, {2, 0, 2}, {3, 0, 2},
       {1, 0, 3}, {2, 0, 3}, {3, 0, 3}, {3, 1, 1}, {2, 2, 1}, {1, 3, 1}, {3, 1, 2}, {2, 2, 2}, {1, 3, 2},
       {3, 1, 3}, {2, 2, 3}, {1, 3, 3}, {0, 3, 1}, {0, 2, 1}, {0, 1, 1}, {0, 3, 2}, {0, 2, 2}, {0, 1, 2},
       {0, 3, 3}, {0, 2, 3}, {0, 1, 3}, {1, 1, 1}, {2, 1, 1}, {1, 2, 1}, {1, 1, 2}, {2, 1, 2}, {1, 2, 2},
       {1, 1, 3}, {2, 1, 3}, {1, 2, 3}}};
  for (const int order : {3, 4}) {
    SCOPED_TRACE(order);
    const auto& expected = vtk_wedges[static_cast<std::size_t>(order - 3)];
    const Eigen::MatrixXd vtk = vtk_lagrange_points(ElementType::Prism, order);
    const Eigen::MatrixXd& gmsh = reference_element(ElementType::Prism, order).nodes;
    const auto& perm = vtk_to_gmsh_permutation(ElementType::Prism, order);
    ASSERT_EQ(static_cast<std::size_t>(vtk.cols()), expected.size());
    for (std::size_t i = 0; i < expected.size(); ++i) {
      const Eigen::Vector3d v(expected[i][0], expected[i][1], expected[i][2]);
      EXPECT_LT((vtk.col(static_cast<Eigen::Index>(i)) * order - v).norm(), 1e-12) << i;
      const Eigen::Vector3d g = gmsh.col(perm[i]);
      EXPECT_LT((Eigen::Vector3d(g(0), g(1), (g(2) + 1) / 2) * order - v).norm(), 1e-12) << i;
    }
  }
}

}  // namespace
}  // namespace meshmorph
