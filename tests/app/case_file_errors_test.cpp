// SPDX-License-Identifier: MIT
// Every key of the case file with a wrong type or value: the InputError names the case
// file and the key path, and says what was expected.
#include <gtest/gtest.h>

#include "app/temp_dir.h"
#include "meshmorph/app/case_file.h"
#include "meshmorph/error.h"

namespace meshmorph {
namespace {

struct BadCase {
  const char* name;
  const char* json;      // the case, with "M" standing for "mesh": "m.msh"
  const char* expected;  // fragment of the message after "case.json: "
};

std::ostream& operator<<(std::ostream& os, const BadCase& c) { return os << c.name; }

const BadCase kBadCases[] = {
    {"TopLevelArray", R"([1, 2])", "(top level): expected an object, found an array"},
    {"UnknownTopKey", R"({M, "ouput": "x.vtu"})", "ouput: unknown key (expected one of: "},
    {"MissingMesh", R"({"steps": 1})", "(top level): missing key \"mesh\""},
    {"MeshNotString", R"({"mesh": 3})", "mesh: expected a string, found a number"},
    {"MeshNotFound", R"({"mesh": "nope.msh"})", "mesh: file not found: "},
    {"OrderString", R"({M, "order": "2"})", "order: expected an integer, found a string"},
    {"OrderFraction", R"({M, "order": 2.5})", "order: expected an integer, found 2.5"},
    {"OrderZero", R"({M, "order": 0})", "order: expected an order from 1 to 4, found 0"},
    {"OrderFive", R"({M, "order": 5})", "order: expected an order from 1 to 4, found 5"},
    {"StepsZero", R"({M, "steps": 0})", "steps: expected a step count from 1 to 1000000, found 0"},
    {"StepsNegative", R"({M, "steps": -3})", "steps: expected a step count"},
    {"StepsBool", R"({M, "steps": true})", "steps: expected an integer, found a boolean"},
    {"EachStepNumber", R"({M, "output_each_step": 1})", "output_each_step: expected true or false, found a number"},
    {"OptionsArray", R"({M, "options": []})", "options: expected an object, found an array"},
    {"OutputNumber", R"({M, "output": 1})", "output: expected a string, found a number"},
    {"OutputExtension", R"({M, "output": "out.stl"})", "output: expected a .msh, .vtu or .mesh file name"},
    {"ReportNull", R"({M, "report": null})", "report: expected a string, found null"},
    {"BoundaryObject", R"({M, "boundary": {}})", "boundary: expected a list of boundary entries, found an object"},
    {"EntryNotObject", R"({M, "boundary": ["inner"]})", "boundary[0]: expected an object"},
    {"EntryMissingGroup", R"({M, "boundary": [{"fixed": true}]})", "boundary[0]: missing key \"group\""},
    {"EntryUnknownKey", R"({M, "boundary": [{"group": "a", "fixed": true}, {"group": "b", "rotat": {}}]})",
     "boundary[1].rotat: unknown key (expected one of: group, fixed, translate"},
    {"EntryNoMotion", R"({M, "boundary": [{"group": "a"}]})", "boundary[0]: missing motion"},
    {"EntryTwoMotions", R"({M, "boundary": [{"group": "a", "fixed": true, "slide": true}]})",
     "boundary[0].slide: a boundary entry takes one motion; \"fixed\" is already given"},
    {"GroupArray", R"({M, "boundary": [{"group": [1], "fixed": true}]})",
     "boundary[0].group: expected a group name (string) or number, found an array"},
    {"GroupZero", R"({M, "boundary": [{"group": 0, "fixed": true}]})",
     "boundary[0].group: expected a positive physical-group number"},
    {"GroupEmpty", R"({M, "boundary": [{"group": "", "fixed": true}]})", "boundary[0].group: expected a group name"},
    {"FixedFalse", R"({M, "boundary": [{"group": "a", "fixed": false}]})", "boundary[0].fixed: expected true"},
    {"SlideString", R"({M, "boundary": [{"group": "a", "slide": "yes"}]})",
     "boundary[0].slide: expected true or false, found a string"},
    {"TranslateShort", R"({M, "boundary": [{"group": "a", "translate": [1]}]})",
     "boundary[0].translate: expected 2 or 3 numbers, found 1 entries"},
    {"TranslateNaNString", R"({M, "boundary": [{"group": "a", "translate": [1, "NaN"]}]})",
     "boundary[0].translate[1]: expected a number, found a string"},
    {"RotateNoCenter", R"({M, "boundary": [{"group": "a", "rotate": {"degrees": 3}}]})",
     "boundary[0].rotate: missing key \"center\""},
    {"RotateAxisTwo", R"({M, "boundary": [{"group": "a", "rotate": {"center": [0,0,0], "axis": [0,1], "degrees": 3}}]})",
     "boundary[0].rotate.axis: expected 3 numbers"},
    {"RotateAxisZero", R"({M, "boundary": [{"group": "a", "rotate": {"center": [0,0,0], "axis": [0,0,0], "degrees": 3}}]})",
     "boundary[0].rotate.axis: expected a non-zero vector"},
    {"RotateDegreesString", R"({M, "boundary": [{"group": "a", "rotate": {"center": [0,0], "degrees": "90"}}]})",
     "boundary[0].rotate.degrees: expected a number, found a string"},
    {"RotateUnknownKey", R"({M, "boundary": [{"group": "a", "rotate": {"center": [0,0], "degrees": 9, "angle": 1}}]})",
     "boundary[0].rotate.angle: unknown key (expected one of: axis, center, degrees)"},
    {"ScaleZero", R"({M, "boundary": [{"group": "a", "scale": {"center": [0,0], "factor": 0}}]})",
     "boundary[0].scale.factor: expected a positive number, found 0"},
    {"ScaleNotObject", R"({M, "boundary": [{"group": "a", "scale": 2}]})",
     "boundary[0].scale: expected an object, found a number"},
    {"ProjectString", R"({M, "boundary": [{"group": "a", "project": "sphere"}]})",
     "boundary[0].project: expected a level-set object"},
    {"ProjectUnknownKind", R"({M, "boundary": [{"group": "a", "project": {"ball": {}}}]})",
     "boundary[0].project.ball: unknown level-set kind (expected one of: sphere, cylinder"},
    {"ProjectTwoKinds", R"({M, "boundary": [{"group": "a", "project": {"expr": "x", "sphere": {}}}]})",
     "boundary[0].project: expected exactly one level-set kind"},
    {"SphereRadiusNegative", R"({M, "interface": {"sphere": {"center": [0,0], "radius": -1}}})",
     "interface.sphere.radius: expected a positive number, found -1"},
    {"SphereUnknownKey", R"({M, "interface": {"sphere": {"center": [0,0], "radius": 1, "r": 1}}})",
     "interface.sphere.r: unknown key"},
    {"CylinderNoAxis", R"({M, "trim": {"cylinder": {"center": [0,0,0], "radius": 1}}})",
     "trim.cylinder: missing key \"axis\""},
    {"PlaneZeroNormal", R"({M, "trim": {"plane": {"point": [0,0], "normal": [0,0]}}})",
     "trim.plane.normal: expected a non-zero vector"},
    {"BoxNegativeSize", R"({M, "trim": {"box": {"center": [0,0], "size": [1,-1]}}})",
     "trim.box.size: expected positive edge lengths"},
    {"BoxSizeLength", R"({M, "trim": {"box": {"center": [0,0], "size": [1,1,1]}}})",
     "trim.box.size: expected as many entries as \"center\""},
    {"TorusNoMinor", R"({M, "trim": {"torus": {"center": [0,0,0], "axis": [0,0,1], "major": 2}}})",
     "trim.torus: missing key \"minor\""},
    {"ExprSyntax", R"({M, "interface": {"expr": "x + * y"}})", "interface.expr: invalid expression \"x + * y\": "},
    {"ExprUnknownName", R"({M, "interface": {"expr": "x + w"}})", "interface.expr: invalid expression \"x + w\": "},
    {"ExprUnknownFunction", R"j({M, "interface": {"expr": "foo(x)"}})j", "interface.expr: invalid expression"},
    {"ExprEmpty", R"({M, "interface": {"expr": "  "}})", "interface.expr: empty expression"},
    {"ExprTwoValues", R"({M, "interface": {"expr": "x, y"}})",
     "interface.expr: expression \"x, y\" gives 2 values (separated by commas); a level set is one"},
    {"ExprNumber", R"({M, "interface": {"expr": 3}})", "interface.expr: expected an expression string"},
    {"BlendOnSphere", R"({M, "interface": {"sphere": {"center": [0,0], "radius": 1}, "blend": 0.1}})",
     "interface.blend: \"blend\" goes with \"union\", \"intersection\" or \"difference\", not \"sphere\""},
    {"BlendZero", R"({M, "interface": {"union": [{"expr": "x"}], "blend": 0}})",
     "interface.blend: expected a positive number, found 0"},
    {"BlendTwoKinds", R"({M, "interface": {"union": [{"expr": "x"}], "expr": "y"}})",
     "interface: expected exactly one level-set kind"},
    {"UnionNotList", R"({M, "interface": {"union": {"expr": "x"}}})",
     "interface.union: expected a list of level sets, found an object"},
    {"UnionEmpty", R"({M, "interface": {"union": []}})", "interface.union: expected at least 1 level set"},
    {"DifferenceThree", R"({M, "interface": {"difference": [{"expr": "x"}, {"expr": "y"}, {"expr": "z"}]}})",
     "interface.difference: expected exactly 2 level sets, found 3"},
    {"NestedBadOperand", R"({M, "interface": {"union": [{"expr": "x"}, {"intersection": [{"plane": {"point": [0,0]}}]}]}})",
     "interface.union[1].intersection[0].plane: missing key \"normal\""},
    {"MeshLevelSetMissingFile", R"({M, "interface": {"mesh": {"file": "none.msh", "field": "phi"}}})",
     "interface.mesh.file: file not found: "},
    {"MeshLevelSetNoField", R"({M, "interface": {"mesh": {"file": "m.msh"}}})", "interface.mesh: missing key \"field\""},
    {"DisplaceMissingFile", R"({M, "boundary": [{"group": "a", "displace": {"file": "none.csv"}}]})",
     "boundary[0].displace.file: file not found: "},
    {"DisplaceFileNumber", R"({M, "boundary": [{"group": "a", "displace": {"file": 1}}]})",
     "boundary[0].displace.file: expected a string, found a number"},
    {"DisplaceUnknownKey", R"({M, "boundary": [{"group": "a", "displace": {"file": "d.csv", "scale": 2}}]})",
     "boundary[0].displace.scale: unknown key (expected one of: file)"},
};

class CaseFileErrors : public ::testing::TestWithParam<BadCase> {};

TEST_P(CaseFileErrors, MessageNamesFileAndKeyPath) {
  test::TempDir dir;
  dir.write("m.msh", "x\n");
  dir.write("d.csv", "1,0,0\n");
  std::string text = GetParam().json;
  if (auto at = text.find("{M"); at != std::string::npos) text.replace(at, 2, R"({"mesh": "m.msh")");
  const auto file = dir.path() / "case.json";
  try {
    parse_case_file(text, file);
    FAIL() << "no error for " << text;
  } catch (const InputError& e) {
    const std::string prefix = file.string() + ": ";
    const std::string what = e.what();
    EXPECT_EQ(what.rfind(prefix, 0), 0u) << what;
    EXPECT_NE(what.find(GetParam().expected, prefix.size()), std::string::npos)
        << "message: " << what << "\nexpected: " << GetParam().expected;
  }
}

INSTANTIATE_TEST_SUITE_P(AllKeys, CaseFileErrors, ::testing::ValuesIn(kBadCases),
                         [](const auto& p) { return std::string(p.param.name); });

// A key the method would ignore is named with the methods it is for; the others pass.
TEST(CaseFileKeys, AKeyTheMethodIgnoresIsAnError) {
  test::TempDir dir;
  dir.write("m.msh", "x\n");
  const auto file = dir.path() / "case.json";
  const CaseFile c = parse_case_file(R"({"mesh": "m.msh", "steps": 2, "trim": {"expr": "x"}})", file);
  EXPECT_EQ(c.keys, (std::vector<std::string>{"mesh", "steps", "trim"}));
  const auto message = [&](const std::string& method, std::initializer_list<std::string_view> unused) -> std::string {
    try {
      reject_unused_keys(c, method, unused);
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_EQ(message("morph", {"interface", "trim"}),
            file.string() + ": trim: morph does not use this key; it is for fit (docs/case-file.md)");
  EXPECT_EQ(message("fit", {"steps", "output_each_step"}),
            file.string() + ": steps: fit does not use this key; it is for morph, untangle and deform (docs/case-file.md)");
  EXPECT_EQ(message("morph", {"interface"}), "");
}

}  // namespace
}  // namespace meshmorph
