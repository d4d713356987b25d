// SPDX-License-Identifier: MIT
#include "meshmorph/app/case_file.h"

#include <cmath>

#include <gtest/gtest.h>

#include "app/temp_dir.h"
#include "meshmorph/error.h"

namespace meshmorph {
namespace {

// A case folder holding the files that valid cases name.
class CaseFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_.write("m.msh", "placeholder: only its existence is checked by the parser\n");
    dir_.write("bg.msh", "placeholder\n");
    dir_.write("lid.csv", "node,dx,dy,dz\n1,0.5,0,0\n2,0.5,0,0\n");
  }
  CaseFile parse(const std::string& text) const { return parse_case_file(text, dir_.path() / "case.json"); }
  // The message of the InputError that parsing `text` throws ("" if none).
  std::string error_of(const std::string& text) const {
    try {
      parse(text);
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  }
  test::TempDir dir_;
};

TEST_F(CaseFileTest, ReadsEveryKeyOfTheDesignExample) {
  const CaseFile c = parse(R"j({
    "mesh": "m.msh", "order": 2,
    "boundary": [
      {"group": "inner",  "translate": [8, 0, 0]},
      {"group": "outer",  "fixed": true},
      {"group": "blades", "rotate": {"center": [0, 0, 0], "axis": [0, 0, 1], "degrees": 72}},
      {"group": "wall",   "scale": {"center": [1, 2, 3], "factor": 1.5}},
      {"group": "sphere", "project": {"sphere": {"center": [0, 0, 0], "radius": 1.0}}},
      {"group": "top",    "project": {"expr": "y - 0.75 - 0.25*sin(pi*(0.5+2*x))"}},
      {"group": "lid",    "displace": {"file": "lid.csv"}},
      {"group": 7,        "slide": true}
    ],
    "interface": {"union": [{"box": {"center": [0.5, 0.5, 0.5], "size": [1, 1, 2]}},
                            {"blend": 0.05,
                             "difference": [{"torus": {"center": [0,0,0], "axis": [0,0,1], "major": 2, "minor": 0.5}},
                                            {"cylinder": {"center": [0,0,0], "axis": [1,0,0], "radius": 0.1}}]}]},
    "trim": {"intersection": [{"plane": {"point": [0,0,0], "normal": [0,0,1]}},
                              {"mesh": {"file": "bg.msh", "field": "phi"}}]},
    "steps": 4, "output_each_step": true,
    "options": {"max_newton": 20},
    "output": "out/out.vtu", "report": "report.json"
  })j");
  EXPECT_EQ(c.mesh, dir_.path() / "m.msh");
  EXPECT_EQ(c.order, 2);
  ASSERT_EQ(c.boundary.size(), 8u);
  EXPECT_EQ(c.boundary[0].group, "inner");
  EXPECT_EQ(c.boundary[0].key_path, "boundary[0]");
  EXPECT_EQ(std::get<TranslateMotion>(c.boundary[0].motion).displacement, Eigen::Vector3d(8, 0, 0));
  EXPECT_TRUE(std::holds_alternative<FixedMotion>(c.boundary[1].motion));
  const auto& rot = std::get<RotateMotion>(c.boundary[2].motion);
  EXPECT_EQ(rot.center, Eigen::Vector3d::Zero());
  ASSERT_TRUE(rot.axis);
  EXPECT_EQ(*rot.axis, Eigen::Vector3d(0, 0, 1));
  EXPECT_EQ(rot.degrees, 72);
  const auto& scale = std::get<ScaleMotion>(c.boundary[3].motion);
  EXPECT_EQ(scale.center, Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(scale.factor, 1.5);
  const auto& proj = std::get<ProjectMotion>(c.boundary[4].motion);
  EXPECT_EQ(proj.target.key_path, "boundary[4].project");
  EXPECT_EQ(std::get<SphereLevelSet>(proj.target.shape).radius, 1.0);
  EXPECT_EQ(std::get<ExprLevelSet>(std::get<ProjectMotion>(c.boundary[5].motion).target.shape).expression,
            "y - 0.75 - 0.25*sin(pi*(0.5+2*x))");
  const auto& table = std::get<DisplaceMotion>(c.boundary[6].motion).table;
  EXPECT_EQ(table.file, dir_.path() / "lid.csv");
  EXPECT_EQ(table.node_tags, (std::vector<std::int64_t>{1, 2}));
  EXPECT_EQ(c.boundary[7].group, "7");
  EXPECT_TRUE(std::holds_alternative<SlideMotion>(c.boundary[7].motion));

  ASSERT_TRUE(c.interface);
  const auto& u = std::get<UnionLevelSet>(c.interface->shape);
  ASSERT_EQ(u.operands.size(), 2u);
  EXPECT_EQ(std::get<BoxLevelSet>(u.operands[0].shape).size, Eigen::Vector3d(1, 1, 2));
  EXPECT_EQ(u.blend, 0.0);
  const auto& diff = std::get<DifferenceLevelSet>(u.operands[1].shape);
  EXPECT_EQ(diff.blend, 0.05);
  EXPECT_EQ(diff.operands[1].key_path, "interface.union[1].difference[1]");
  EXPECT_EQ(std::get<TorusLevelSet>(diff.operands[0].shape).minor, 0.5);
  EXPECT_EQ(std::get<CylinderLevelSet>(diff.operands[1].shape).axis, Eigen::Vector3d(1, 0, 0));
  ASSERT_TRUE(c.trim);
  const auto& inter = std::get<IntersectionLevelSet>(c.trim->shape);
  EXPECT_EQ(std::get<PlaneLevelSet>(inter.operands[0].shape).normal, Eigen::Vector3d(0, 0, 1));
  const auto& bg = std::get<MeshLevelSet>(inter.operands[1].shape);
  EXPECT_EQ(bg.file, dir_.path() / "bg.msh");
  EXPECT_EQ(bg.field, "phi");

  EXPECT_EQ(c.steps, 4);
  EXPECT_TRUE(c.output_each_step);
  EXPECT_EQ(c.options.at("max_newton"), 20);
  EXPECT_EQ(c.output, dir_.path() / "out/out.vtu");
  EXPECT_EQ(c.report, dir_.path() / "report.json");
}

TEST_F(CaseFileTest, DefaultsWhenOnlyTheMeshIsGiven) {
  const CaseFile c = parse(R"({"mesh": "m.msh"})");
  EXPECT_FALSE(c.order);
  EXPECT_TRUE(c.boundary.empty());
  EXPECT_FALSE(c.interface);
  EXPECT_FALSE(c.trim);
  EXPECT_EQ(c.steps, 1);
  EXPECT_FALSE(c.output_each_step);
  EXPECT_TRUE(c.options.is_object() && c.options.empty());
  EXPECT_FALSE(c.output);
  EXPECT_FALSE(c.report);
}

TEST_F(CaseFileTest, AcceptsTwoDimensionalVectorsAndRotationWithoutAxis) {
  const CaseFile c = parse(R"({"mesh": "m.msh", "boundary": [
      {"group": "inner", "rotate": {"center": [0, 0], "degrees": -120.5}},
      {"group": "outer", "project": {"sphere": {"center": [0, 0], "radius": 2}}}]})");
  const auto& rot = std::get<RotateMotion>(c.boundary[0].motion);
  EXPECT_EQ(rot.center.size(), 2);
  EXPECT_FALSE(rot.axis);
  EXPECT_EQ(rot.degrees, -120.5);
}

// Axes and normals are directions: unit vectors, also where |v| overflows or underflows.
TEST_F(CaseFileTest, DirectionsAreUnitVectorsWhateverTheirLength) {
  const CaseFile c = parse(R"({"mesh": "m.msh", "boundary": [
      {"group": "blades", "rotate": {"center": [0, 0, 0], "axis": [0, 0, 1e-320], "degrees": 72}},
      {"group": "lid", "project": {"plane": {"point": [0, 0, 0], "normal": [1e308, 1e308, 0]}}}]})");
  const CaseVector& axis = *std::get<RotateMotion>(c.boundary[0].motion).axis;
  EXPECT_EQ(axis, Eigen::Vector3d(0, 0, 1));
  const auto& plane = std::get<PlaneLevelSet>(std::get<ProjectMotion>(c.boundary[1].motion).target.shape);
  EXPECT_NEAR(plane.normal[0], std::sqrt(0.5), 1e-15);
  EXPECT_NEAR(plane.normal[1], std::sqrt(0.5), 1e-15);
  EXPECT_EQ(plane.normal[2], 0.0);
}

TEST_F(CaseFileTest, ReadsTheCaseFromDiskWithPathsRelativeToIt) {
  const auto file = dir_.write("sub/case.json", R"({"mesh": "../m.msh", "output": "o.msh"})");
  const CaseFile c = read_case_file(file);
  EXPECT_EQ(c.file, file);
  EXPECT_EQ(c.mesh, dir_.path() / "sub" / "../m.msh");
  EXPECT_TRUE(std::filesystem::is_regular_file(c.mesh));
  EXPECT_EQ(c.output, dir_.path() / "sub" / "o.msh");
}

TEST_F(CaseFileTest, MissingCaseFileIsAnIoError) {
  EXPECT_THROW(read_case_file(dir_.path() / "nope.json"), IoError);
}

TEST_F(CaseFileTest, SyntaxErrorsNameLineAndColumn) {
  EXPECT_EQ(error_of("{\n  \"mesh\": \"m.msh\",\n  \"steps\": 2,\n}").rfind(
                (dir_.path() / "case.json").string() + ":4:1: invalid JSON: ", 0),
            0u)
      << error_of("{\n  \"mesh\": \"m.msh\",\n  \"steps\": 2,\n}");
  EXPECT_NE(error_of("{\n \"mesh\": \"m.msh\" \"order\": 1}").find("case.json:2:24: invalid JSON: syntax error while parsing object"), std::string::npos)
      << error_of("{\n \"mesh\": \"m.msh\" \"order\": 1}");
  EXPECT_NE(error_of("").find("case.json:1:1: invalid JSON"), std::string::npos) << error_of("");
  EXPECT_NE(error_of("{\"mesh\": NaN}").find("case.json:1:10: invalid JSON"), std::string::npos)
      << error_of("{\"mesh\": NaN}");
}

TEST_F(CaseFileTest, NumbersTooLargeForADoubleNameTheirPlace) {
  const std::string e = error_of("{\"mesh\": \"m.msh\",\n \"steps\": 1e999}");
  EXPECT_NE(e.find("case.json:2:11: invalid JSON: number out of range: 1e999"), std::string::npos) << e;
}

// Level sets are read and evaluated recursively: a CSG tree of `levels` unions of one sphere.
std::string nested_unions(int levels) {
  std::string ls = R"({"sphere": {"center": [0, 0], "radius": 1}})";
  for (int i = 0; i < levels; ++i) ls = R"({"union": [)" + ls + "]}";
  return R"({"mesh": "m.msh", "interface": )" + ls + "}";
}

TEST_F(CaseFileTest, NestingDeeperThanACaseNeedsIsRejectedBeforeItIsRead) {
  EXPECT_EQ(error_of(nested_unions(60)), "");
  const std::string e = error_of(nested_unions(10000));
  EXPECT_EQ(e.rfind((dir_.path() / "case.json").string() + ": interface.union[0].union[0].", 0), 0u) << e.substr(0, 200);
  EXPECT_NE(e.find(": nested more than 128 levels deep"), std::string::npos) << e.substr(0, 200);
}

TEST_F(CaseFileTest, DuplicateKeysAreRejectedWithTheirPath) {
  EXPECT_NE(error_of(R"({"mesh": "m.msh", "mesh": "m.msh"})").find("case.json: mesh: duplicate key"),
            std::string::npos);
  const std::string e = error_of(R"({"mesh": "m.msh", "boundary": [{"group": "a", "fixed": true},
      {"group": "b", "rotate": {"center": [0,0], "degrees": 1, "degrees": 2}}]})");
  EXPECT_NE(e.find("case.json: boundary[1].rotate.degrees: duplicate key"), std::string::npos) << e;
}

// The Python module's Morpher brings its mesh in memory: its case has no "mesh" key, and a
// "mesh" that is there must still exist.
TEST_F(CaseFileTest, AMeshIsOptionalWhereTheCallerHasOne) {
  const std::string text = R"({"boundary": [{"group": "inner", "translate": [1, 0]}], "options": {"alpha": 4}})";
  const CaseFile c = parse_case_file(text, dir_.path() / "Morpher", false);
  EXPECT_TRUE(c.mesh.empty());
  ASSERT_EQ(c.boundary.size(), 1u);
  EXPECT_EQ(c.options["alpha"], 4);
  EXPECT_NE(error_of(text).find("missing key \"mesh\""), std::string::npos);
  EXPECT_THROW(parse_case_file(R"({"mesh": "none.msh"})", dir_.path() / "Morpher", false), InputError);
}

}  // namespace
}  // namespace meshmorph
