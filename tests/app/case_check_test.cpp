// SPDX-License-Identifier: MIT
// check_case_against_mesh: groups, dimensions and CSV nodes against a loaded mesh.
#include <gtest/gtest.h>

#include "app/temp_dir.h"
#include "meshmorph/app/case_file.h"
#include "meshmorph/error.h"

namespace meshmorph {
namespace {

// The unit square as two triangles; the bottom edge is "inner" (1), the others "outer" (2).
Mesh unit_square() {
  Mesh m;
  m.dim = 2;
  m.x.resize(2, 4);
  m.x << 0, 1, 1, 0, 0, 0, 1, 1;
  m.node_tags = {1, 2, 3, 4};
  CellBlock tris;
  const std::int32_t t[2][3] = {{0, 1, 2}, {0, 2, 3}};
  for (const auto& c : t) tris.push_back(c, 10);
  m.cells.push_back(tris);
  CellBlock lines;
  lines.type = ElementType::Line;
  const std::int32_t l[4][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}};
  for (int i = 0; i < 4; ++i) lines.push_back(l[i], i == 0 ? 1 : 2);
  m.facets.push_back(lines);
  m.groups = {{1, 1, "inner"}, {1, 2, "outer"}, {2, 10, "domain"}};
  return m;
}

// One tetrahedron; its faces form group 5 "skin".
Mesh one_tet() {
  Mesh m;
  m.dim = 3;
  m.x = Eigen::MatrixXd::Identity(3, 4);
  m.x.col(0).setZero();
  m.x.col(1) << 1, 0, 0;
  m.x.col(2) << 0, 1, 0;
  m.x.col(3) << 0, 0, 1;
  m.node_tags = {1, 2, 3, 4};
  CellBlock tets;
  tets.type = ElementType::Tetrahedron;
  const std::int32_t t[4] = {0, 1, 2, 3};
  tets.push_back(t, 0);
  m.cells.push_back(tets);
  CellBlock faces;
  faces.type = ElementType::Triangle;
  const std::int32_t f[3] = {0, 2, 1};
  faces.push_back(f, 5);
  m.facets.push_back(faces);
  m.groups = {{2, 5, "skin"}};
  return m;
}

class CaseCheck : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_.write("m.msh", "x\n");
    dir_.write("d2.csv", "node,dx,dy\n1,0.1,0\n2,0.1,0\n");
    dir_.write("d3.csv", "1,0,0,0\n");
    dir_.write("far.csv", "1,0,0\n\n9,0,0\n");
    dir_.write("other.csv", "1,0,0\n3,0,0\n");
  }
  // The message of check_case_against_mesh (or of the parser), "" when the case passes.
  std::string error_of(const std::string& body, const Mesh& mesh) const {
    try {
      const CaseFile c = parse_case_file(R"({"mesh": "m.msh", )" + body + "}", dir_.path() / "case.json");
      check_case_against_mesh(c, mesh);
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  }
  std::string prefix() const { return (dir_.path() / "case.json").string() + ": "; }
  test::TempDir dir_;
};

TEST_F(CaseCheck, AcceptsAValidTwoDimensionalCase) {
  EXPECT_EQ(error_of(R"("order": 3, "boundary": [{"group": "inner", "rotate": {"center": [0.5, 0.5], "degrees": 30}},
      {"group": 2, "fixed": true}, {"group": "domain", "displace": {"file": "d2.csv"}}],
      "interface": {"union": [{"plane": {"point": [0, 0], "normal": [1, 1]}}, {"expr": "x*y"}]})",
                     unit_square()),
            "");
}

TEST_F(CaseCheck, MissingGroupListsTheGroupsOfTheMesh) {
  EXPECT_EQ(error_of(R"("boundary": [{"group": "inner", "fixed": true}, {"group": "blade", "fixed": true}])", unit_square()),
            prefix() + "boundary[1].group: no physical group \"blade\" in m.msh (it has: inner (1), outer (2), domain (10))");
  EXPECT_EQ(error_of(R"("boundary": [{"group": 7, "slide": true}])", unit_square()),
            prefix() + "boundary[0].group: no physical group \"7\" in m.msh (it has: inner (1), outer (2), domain (10))");
}

// A group named in the file but carried by no element (an MSH 4.1 file without $Entities):
// a motion of it would move nothing and report the boundary reached.
TEST_F(CaseCheck, AGroupWithoutElementsIsAnError) {
  Mesh m = unit_square();
  m.groups.push_back({1, 3, "lid"});
  EXPECT_EQ(error_of(R"("boundary": [{"group": "inner", "fixed": true}, {"group": "lid", "translate": [0, 1]}])", m),
            prefix() + "boundary[1].group: physical group \"lid\" of m.msh has no elements: no element of the mesh "
                       "carries its tag");
}

TEST_F(CaseCheck, AMeditOutputMustBeLinear) {
  EXPECT_EQ(error_of(R"("order": 2, "output": "out.mesh")", unit_square()),
            prefix() + "output: Medit .mesh holds linear cells only; the result is of order 2 (write .msh or .vtu)");
  EXPECT_EQ(error_of(R"("order": 1, "output": "out.mesh")", unit_square()), "");
  EXPECT_EQ(error_of(R"("order": 2, "output": "out.msh")", unit_square()), "");
}

TEST_F(CaseCheck, VectorsMustMatchTheMeshDimension) {
  EXPECT_EQ(error_of(R"("boundary": [{"group": "inner", "translate": [1, 0, 0]}])", unit_square()),
            prefix() + "boundary[0].translate: expected 2 numbers for a 2D mesh, found 3");
  EXPECT_EQ(error_of(R"("interface": {"union": [{"expr": "x"}, {"sphere": {"center": [0,0,0], "radius": 1}}]})",
                     unit_square()),
            prefix() + "interface.union[1].sphere.center: expected 2 numbers for a 2D mesh, found 3");
  EXPECT_EQ(error_of(R"("boundary": [{"group": "skin", "scale": {"center": [0, 0], "factor": 2}}])", one_tet()),
            prefix() + "boundary[0].scale.center: expected 3 numbers for a 3D mesh, found 2");
}

TEST_F(CaseCheck, RotationAxisExactlyInThreeDimensions) {
  EXPECT_EQ(error_of(R"("boundary": [{"group": "inner", "rotate": {"center": [0, 0], "axis": [0, 0, 1], "degrees": 9}}])",
                     unit_square()),
            prefix() + "boundary[0].rotate.axis: a 2D rotation takes no axis");
  EXPECT_EQ(error_of(R"("boundary": [{"group": "skin", "rotate": {"center": [0, 0, 0], "degrees": 9}}])", one_tet()),
            prefix() + "boundary[0].rotate: missing key \"axis\" (needed in 3D)");
  EXPECT_EQ(error_of(R"("boundary": [{"group": "skin", "rotate": {"center": [0, 0, 0], "axis": [1, 0, 0], "degrees": 9}}])",
                     one_tet()),
            "");
}

TEST_F(CaseCheck, CylinderAndTorusOnlyInThreeDimensions) {
  EXPECT_EQ(error_of(R"("trim": {"cylinder": {"center": [0, 0], "axis": [0, 1], "radius": 1}})", unit_square()),
            prefix() + "trim.cylinder: an infinite cylinder exists only in 3D; the mesh is 2D");
  EXPECT_EQ(error_of(R"("trim": {"torus": {"center": [0, 0, 0], "axis": [0, 0, 1], "major": 2, "minor": 1}})", one_tet()), "");
}

TEST_F(CaseCheck, DisplacementNodesAndComponentsMatchTheMesh) {
  const std::string far = (dir_.path() / "far.csv").string();
  EXPECT_EQ(error_of(R"("boundary": [{"group": "inner", "displace": {"file": "far.csv"}}])", unit_square()),
            far + ":3: node 9 is not in m.msh (" + prefix() + "boundary[0].displace.file)");
  // A node of the mesh, but of another group: an error too, not a motion of a fixed node.
  const std::string other = (dir_.path() / "other.csv").string();
  EXPECT_EQ(error_of(R"("boundary": [{"group": "inner", "displace": {"file": "other.csv"}}])", unit_square()),
            other + ":2: node 3 is not in group \"inner\" (" + prefix() + "boundary[0].displace.file)");
  const std::string e = error_of(R"("boundary": [{"group": "inner", "displace": {"file": "d3.csv"}}])", unit_square());
  EXPECT_EQ(e.rfind(prefix() + "boundary[0].displace.file: ", 0), 0u) << e;
  EXPECT_NE(e.find("expected 2 displacement components per row for a 2D mesh, found 3"), std::string::npos) << e;
}

TEST_F(CaseCheck, OrderWithinTheLimitOfTheCellType) {
  Mesh quads = unit_square();
  quads.cells[0] = CellBlock{};
  quads.cells[0].type = ElementType::Quadrilateral;
  const std::int32_t q[4] = {0, 1, 2, 3};
  quads.cells[0].push_back(q, 10);
  EXPECT_EQ(error_of(R"("order": 4)", quads), prefix() + "order: order 4 is above the highest for quadrilateral cells (3)");
  EXPECT_EQ(error_of(R"("order": 3)", quads), "");
  EXPECT_EQ(error_of(R"("order": 4)", unit_square()), "");
}

}  // namespace
}  // namespace meshmorph
