// SPDX-License-Identifier: MIT
// The malformed case files of tests/data/bad_cases: each one is rejected, by the parser, by the
// check against its mesh or by resolving its motions (as `meshmorph check` does), with an
// InputError naming the file and the line:column (JSON syntax), the key path, or the CSV file
// and line.
#include <map>

#include <gtest/gtest.h>

#include "meshmorph/methods/boundary_motion.h"
#include "meshmorph/app/case_file.h"
#include "meshmorph/error.h"
#include "meshmorph/io/mesh_io.h"

namespace meshmorph {
namespace {

const std::filesystem::path kDir = std::filesystem::path(MESHMORPH_TEST_DATA) / "bad_cases";

// File → {file that the message starts with, fragment the message holds}.
struct Expectation {
  const char* named_file;
  const char* fragment;
};
const std::map<std::string, Expectation> kExpected = {
    {"unknown_key.json", {"unknown_key.json", ": ouptut: unknown key (expected one of: "}},
    {"wrong_type_steps.json", {"wrong_type_steps.json", ": steps: expected an integer, found a string"}},
    {"syntax_error.json", {"syntax_error.json", ":4:29: invalid JSON: syntax error while parsing object"}},
    {"missing_mesh.json", {"missing_mesh.json", ": mesh: file not found: "}},
    {"missing_group.json", {"missing_group.json", ": boundary[1].group: no physical group \"blade\" in square.msh"}},
    {"bad_expr.json", {"bad_expr.json", ": boundary[0].project.expr: invalid expression \"y - sin(pi*x\""}},
    {"nan_string.json", {"nan_string.json", ": boundary[0].translate[1]: expected a number, found a string"}},
    {"steps_zero.json", {"steps_zero.json", ": steps: expected a step count from 1 to 1000000, found 0"}},
    {"order_five.json", {"order_five.json", ": order: expected an order from 1 to 4, found 5"}},
    {"rotate_axis_in_2d.json", {"rotate_axis_in_2d.json", ": boundary[0].rotate.axis: a 2D rotation takes no axis"}},
    {"unknown_motion.json", {"unknown_motion.json", ": boundary[0].twist: unknown key (expected one of: group, fixed"}},
    {"two_motions.json", {"two_motions.json", ": boundary[0].translate: a boundary entry takes one motion"}},
    {"duplicate_key.json", {"duplicate_key.json", ": steps: duplicate key"}},
    {"bad_csv.json", {"bad_number.csv", ":3: field 3: expected a number, found \"zero\""}},
    {"csv_unknown_node.json", {"unknown_node.csv", ":3: node 99 is not in square.msh"}},
    {"trailing_garbage.json", {"trailing_garbage.json", ":2:1: invalid JSON: "}},
    {"difference_one.json", {"difference_one.json", ": interface.difference: expected exactly 2 level sets, found 1"}},
    {"empty.json", {"empty.json", ":2:1: invalid JSON: "}},
    {"vector_3d_for_2d.json", {"vector_3d_for_2d.json", ": boundary[0].scale.center: expected 2 numbers for a 2D mesh"}},
    {"negative_radius.json", {"negative_radius.json", ": trim.sphere.radius: expected a positive number, found -0.5"}},
    {"options_array.json", {"options_array.json", ": options: expected an object, found an array"}},
    {"missing_group_number.json", {"missing_group_number.json", ": boundary[0].group: no physical group \"9\""}},
    {"group_without_elements.json",
     {"group_without_elements.json", ": boundary[0].group: physical group \"lid\" of square_unused_group.msh has no elements"}},
    {"medit_order_two.json", {"medit_order_two.json", ": output: Medit .mesh holds linear cells only; the result is of order 2"}},
    {"translate_too_far.json",
     {"translate_too_far.json", ": boundary[0]: node 1: the target's coordinate 1e+300 is beyond +-1e+100"}},
    {"interior_group.json",
     {"interior_group.json", ": boundary[0].group: no node of group \"mid\" is on the boundary of the mesh"}},
    {"conflicting_targets.json", {"conflicting_targets.json", ": boundary[1]: node 1 is also moved by boundary[0] to a different target"}},
};

std::vector<std::string> case_files() {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(kDir))
    if (entry.path().extension() == ".json") names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

class BadCaseFiles : public ::testing::TestWithParam<std::string> {};

TEST_P(BadCaseFiles, RejectedWithFileAndPlace) {
  const auto it = kExpected.find(GetParam());
  ASSERT_NE(it, kExpected.end()) << GetParam() << " has no expectation in this test";
  const auto path = kDir / GetParam();
  try {
    const CaseFile c = read_case_file(path);
    const Mesh mesh = read_mesh(c.mesh);
    check_case_against_mesh(c, mesh);
    BoundaryMotion(c.boundary, c.file.string(), mesh, build_topology(mesh));
    FAIL() << GetParam() << " was accepted";
  } catch (const InputError& e) {
    const std::string what = e.what();
    const std::string named = (kDir / it->second.named_file).string();
    EXPECT_EQ(what.rfind(named, 0), 0u) << what;
    EXPECT_NE(what.find(it->second.fragment), std::string::npos) << "message: " << what
                                                                 << "\nexpected: " << it->second.fragment;
  }
}

INSTANTIATE_TEST_SUITE_P(All, BadCaseFiles, ::testing::ValuesIn(case_files()), [](const auto& p) {
  std::string name = p.param.substr(0, p.param.size() - 5);
  for (char& ch : name)
    if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
  return name;
});

TEST(BadCaseFiles, EveryExpectationHasItsFile) {
  const auto files = case_files();
  EXPECT_GE(files.size(), 12u);
  for (const auto& [name, expectation] : kExpected)
    EXPECT_TRUE(std::find(files.begin(), files.end(), name) != files.end()) << name;
}

}  // namespace
}  // namespace meshmorph
