// SPDX-License-Identifier: MIT
// Node fields (Mesh::node_fields) in the readers and writers: MSH $NodeData as Gmsh writes
// it (time steps, partitions, vector fields, tags in any order), VTU PointData with several
// components, pieces and types, and the writers' checks. Round trips through every format
// and encoding are in round_trip_test.cpp, malformed files in tests/data/bad.
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "meshmorph/error.h"
#include "meshmorph/fem/structured.h"
#include "meshmorph/io/mesh_io.h"
#include "meshmorph/io/msh.h"
#include "meshmorph/io/vtu.h"

namespace meshmorph {
namespace {

namespace fs = std::filesystem;

class NodeFields : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("meshmorph_node_fields_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path write(const std::string& name, const std::string& text) const {
    const fs::path p = dir_ / name;
    std::ofstream(p, std::ios::binary) << text;
    return p;
  }
  fs::path dir_;
};

// Two triangles on nodes tagged 10, 30, 20, 40 (in this order in the file).
const char* const k_msh41_mesh = R"($MeshFormat
4.1 0 8
$EndMeshFormat
$Nodes
1 4 10 40
2 1 0 4
10
30
20
40
0 0 0
1 0 0
1 1 0
0 1 0
$EndNodes
$Elements
1 2 1 2
2 1 2 2
1 10 30 20
2 10 20 40
$EndElements
)";

std::string node_data(const std::string& name, int step, int components, const std::string& records,
                      int n_records, bool partition = false) {
  std::ostringstream s;
  s << "$NodeData\n1\n\"" << name << "\"\n1\n" << step << ".0\n" << (partition ? 4 : 3) << '\n'
    << step << '\n' << components << '\n' << n_records << '\n';
  if (partition) s << "1\n";
  s << records << "$EndNodeData\n";
  return s.str();
}

TEST_F(NodeFields, MshNodeDataLastTimeStepWinsPartitionsMergeVectorsAreDropped) {
  const std::string text = std::string(k_msh41_mesh) +
                           node_data("phi", 0, 1, "10 1\n30 2\n20 3\n40 4\n", 4) +
                           // Step 1 in two partitions, tags in any order.
                           node_data("phi", 1, 1, "40 -4\n10 -1\n", 2, true) +
                           node_data("phi", 1, 1, "30 -2\n20 -3.5e-1\n", 2, true) +
                           node_data("u", 0, 3, "30 1 2 3\n10 4 5 6\n20 7 8 9\n40 1 1 1\n", 4) +
                           node_data("k", 0, 1, "40 nan\n30 inf\n20 7\n10 1e300\n", 4);
  const Mesh m = read_mesh(write("steps.msh", text));
  ASSERT_EQ(m.node_fields.size(), 2u);  // "u" has 3 components
  ASSERT_TRUE(m.node_fields.count("phi"));
  EXPECT_EQ(m.node_fields.at("phi"), (Eigen::Vector4d(-1, -2, -0.35, -4)));
  const Eigen::VectorXd& k = m.node_fields.at("k");
  EXPECT_EQ(k(0), 1e300);
  EXPECT_EQ(k(1), std::numeric_limits<double>::infinity());
  EXPECT_EQ(k(2), 7);
  EXPECT_TRUE(std::isnan(k(3)));
}

TEST_F(NodeFields, MshNodeDataErrorsNameTheFileAndPosition) {
  struct Case {
    const char* data;
    const char* expected;
  };
  const std::string incomplete_step = node_data("phi", 0, 1, "10 1\n30 2\n20 3\n40 4\n", 4) +
                                      node_data("phi", 1, 1, "40 -4\n10 -1\n", 2);
  for (const auto& [data, expected] : std::initializer_list<std::pair<std::string, std::string>>{
           // The last time step has values for two nodes only.
           {incomplete_step, "line 36: $NodeData \"phi\" (time step 1) has no value for node tag 30 (2 of 4 nodes have one)"},
           {"$NodeData\n0\n1\n0\n3\n0\n1\n0\n$EndNodeData\n", "line 23: $NodeData needs a string tag (the field name)"},
           {"$NodeData\n1\nphi\n1\n0\n3\n0\n1\n0\n$EndNodeData\n", "line 24: expected string tag in double quotes"},
           {"$NodeData\n1\n\"phi\n1\n0\n3\n0\n1\n0\n$EndNodeData\n", "line 24: missing closing quote in string tag"},
           {"$NodeData\n1\n\"phi\"\n1\n0\n2\n0\n1\n$EndNodeData\n", "line 27: $NodeData needs 3 integer tags"},
           {"$NodeData\n1\n\"phi\"\n1\n0\n3\n0\n0\n1\n10 1\n$EndNodeData\n", "line 29: number of components must be 1..9"},
           {"$NodeData\n1\n\"phi\"\n1\n0\n3\n0\n1\n1\n10 x\n$EndNodeData\n", "line 31: expected field value (a number), got 'x'"},
           {"$NodeData\n1\n\"phi\"\n1\n0\n3\n0\n1\n900\n10 1\n$EndNodeData\n",
            "line 30: count 900 is larger than the rest of the file can hold"},
           {"$NodeData\n1\n\"phi\"\n1\n0\n3\n0\n1\n2\n10 1\n20 2\n30 3\n$EndNodeData\n", "expected $EndNodeData, got '30'"},
       }) {
    SCOPED_TRACE(expected);
    const fs::path p = write("bad.msh", k_msh41_mesh + data);
    try {
      read_mesh(p);
      ADD_FAILURE() << "no InputError";
    } catch (const InputError& e) {
      const std::string msg = e.what();
      EXPECT_EQ(msg.rfind(p.string() + ": line ", 0), 0u) << msg;
      EXPECT_NE(msg.find(expected), std::string::npos) << msg;
    }
  }
  // $NodeData must follow $Nodes: its records refer to node tags.
  const std::string before = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n" + node_data("phi", 0, 1, "", 0) +
                             std::string(k_msh41_mesh).substr(std::string(k_msh41_mesh).find("$Nodes"));
  EXPECT_THROW(
      {
        try {
          read_mesh(write("before.msh", before));
        } catch (const InputError& e) {
          EXPECT_NE(std::string(e.what()).find("line 4: $NodeData before $Nodes"), std::string::npos) << e.what();
          throw;
        }
      },
      InputError);
}

TEST_F(NodeFields, Msh22NodeDataIsReadLikeMsh41) {
  const std::string text = R"($MeshFormat
2.2 0 8
$EndMeshFormat
$Nodes
3
7 0 0 0
5 1 0 0
6 0 1 0
$EndNodes
$Elements
1
1 2 2 0 1 7 5 6
$EndElements
)" + node_data("phi", 0, 1, "6 0.5\n7 -0.5\n5 +2\n", 3);
  const Mesh m = read_mesh(write("m22.msh", text));
  ASSERT_EQ(m.node_fields.count("phi"), 1u);
  EXPECT_EQ(m.node_fields.at("phi"), Eigen::Vector3d(-0.5, 2, 0.5));
}

std::string vtu_piece(const std::string& point_data) {
  return R"(<Piece NumberOfPoints="3" NumberOfCells="1">
<Points><DataArray type="Float64" NumberOfComponents="3" format="ascii">0 0 0 1 0 0 0 1 0</DataArray></Points>
<Cells><DataArray type="Int32" Name="connectivity" format="ascii">0 1 2</DataArray>
<DataArray type="Int32" Name="offsets" format="ascii">3</DataArray>
<DataArray type="UInt8" Name="types" format="ascii">5</DataArray></Cells>
<PointData>)" + point_data + "</PointData>\n</Piece>\n";
}

std::string vtu_file(const std::string& pieces) {
  return "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\">\n"
         "<UnstructuredGrid>\n" + pieces + "</UnstructuredGrid>\n</VTKFile>\n";
}

TEST_F(NodeFields, VtuPointDataKeepsScalarArraysOfAnyTypeAcrossPieces) {
  const std::string arrays =
      R"(<DataArray type="Float32" Name="phi" format="ascii">0.5 -1.25 nan</DataArray>
<DataArray type="Int16" Name="label" NumberOfComponents="1" format="ascii">3 -2 7</DataArray>
<DataArray type="Float64" Name="velocity" NumberOfComponents="3" format="ascii">1 2 3 4 5 6 7 8 9</DataArray>
<DataArray type="Float64" format="ascii">1 2 3</DataArray>
<DataArray type="String" Name="names" format="ascii">97 0 98 0 99 0</DataArray>
)";
  const Mesh m = read_mesh(write("two.vtu", vtu_file(vtu_piece(arrays) + vtu_piece(arrays))));
  ASSERT_EQ(m.node_fields.size(), 2u);  // velocity has 3 components, one array no name, names is text
  const Eigen::VectorXd& phi = m.node_fields.at("phi");
  ASSERT_EQ(phi.size(), 6);
  EXPECT_EQ(phi(0), 0.5);
  EXPECT_EQ(phi(4), -1.25);
  EXPECT_TRUE(std::isnan(phi(2)) && std::isnan(phi(5)));
  EXPECT_EQ(m.node_fields.at("label"), (Eigen::VectorXd(6) << 3, -2, 7, 3, -2, 7).finished());
}

TEST_F(NodeFields, VtuPointDataErrorsNameTheFileAndLine) {
  const std::string phi = R"(<DataArray type="Float64" Name="phi" format="ascii">1 2 3</DataArray>)";
  for (const auto& [pieces, expected] : std::initializer_list<std::pair<std::string, std::string>>{
           {vtu_piece(phi) + vtu_piece(""), "line 16: Piece has no PointData array 'phi' (the first Piece has one)"},
           {vtu_piece("") + vtu_piece(phi), "line 16: PointData array 'phi' is missing in the first Piece"},
           {vtu_piece(phi + phi), "line 9: PointData holds two arrays named 'phi'"},
           {vtu_piece(R"(<DataArray type="Float64" Name="phi" format="ascii">1 2</DataArray>)"),
            "line 9: DataArray 'phi' holds 2 values, expected 3"},
           {vtu_piece(R"(<DataArray type="Float64" Name="phi" format="ascii">1 2 x</DataArray>)"),
            "line 9: DataArray 'phi': bad value 'x'"},
           {vtu_piece(R"(<DataArray type="Float64" Name="phi" format="binary">QUJ!</DataArray>)"),
            "line 9: DataArray 'phi': invalid base64 data"},
       }) {
    SCOPED_TRACE(expected);
    const fs::path p = write("bad.vtu", vtu_file(pieces));
    try {
      read_mesh(p);
      ADD_FAILURE() << "no InputError";
    } catch (const InputError& e) {
      const std::string msg = e.what();
      EXPECT_EQ(msg.rfind(p.string() + ": line ", 0), 0u) << msg;
      EXPECT_NE(msg.find(expected), std::string::npos) << msg;
    }
  }
}

TEST_F(NodeFields, WritersCheckFieldsBeforeWriting) {
  Mesh m = structured_mesh(ElementType::Triangle, 1, 2);
  m.node_fields["short"] = Eigen::VectorXd::Zero(3);
  for (const MeshFormat f : {MeshFormat::Msh41, MeshFormat::Msh22, MeshFormat::Vtu}) {
    const fs::path p = dir_ / (f == MeshFormat::Vtu ? "short.vtu" : "short.msh");
    EXPECT_THROW(write_mesh(p, m, {f, false, {}, {}}), std::invalid_argument);
    EXPECT_FALSE(fs::exists(p));
  }
  m.node_fields.clear();
  m.node_fields["say \"hi\""] = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(m.n_nodes()));
  EXPECT_THROW(write_mesh(dir_ / "quote.msh", m), InputError);
  EXPECT_FALSE(fs::exists(dir_ / "quote.msh"));
  // VTU escapes the quote; the name reads back.
  write_mesh(dir_ / "quote.vtu", m);
  EXPECT_EQ(read_mesh(dir_ / "quote.vtu").node_fields.count("say \"hi\""), 1u);
  // Binary $NodeData stores tags as int32 (as Gmsh does).
  m.node_fields.clear();
  m.node_fields["phi"] = Eigen::VectorXd::Ones(static_cast<Eigen::Index>(m.n_nodes()));
  m.node_tags[0] = std::int64_t{1} << 33;
  EXPECT_THROW(write_mesh(dir_ / "big.msh", m, {MeshFormat::Msh41, true, {}, {}}), InputError);
  write_mesh(dir_ / "big.msh", m, {MeshFormat::Msh41, false, {}, {}});
  EXPECT_EQ(read_mesh(dir_ / "big.msh").node_tags[0], std::int64_t{1} << 33);
}

// The layout Gmsh and meshio expect: one header item per line, int32 tags in binary.
TEST_F(NodeFields, MshWriterUsesGmshLayout) {
  Mesh m = structured_mesh(ElementType::Triangle, 1, 1);
  m.node_fields["phi"] = Eigen::Vector4d(0.5, 1, 2, 4);
  std::ostringstream ascii;
  write_msh(ascii, m, 41, false);
  EXPECT_NE(ascii.str().find("$NodeData\n1\n\"phi\"\n1\n0\n3\n0\n1\n4\n1 0.5\n2 1\n3 2\n4 4\n$EndNodeData\n"),
            std::string::npos)
      << ascii.str();
  std::ostringstream binary;
  write_msh(binary, m, 22, true);
  const std::string b = binary.str();
  const std::string header = "$NodeData\n1\n\"phi\"\n1\n0\n3\n0\n1\n4\n";
  const std::size_t at = b.find(header);
  ASSERT_NE(at, std::string::npos);
  std::int32_t tag = 0;
  double value = 0;
  std::memcpy(&tag, b.data() + at + header.size() + 12, 4);
  std::memcpy(&value, b.data() + at + header.size() + 16, 8);
  EXPECT_EQ(tag, 2);
  EXPECT_EQ(value, 1.0);
  EXPECT_EQ(b.substr(at + header.size() + 4 * 12), "\n$EndNodeData\n");
}

}  // namespace
}  // namespace meshmorph
