// SPDX-License-Identifier: MIT
// Every examples/*/case.json parses and fits its mesh, and each example's README opens with
// its "Sample run" command.
#include <fstream>

#include <gtest/gtest.h>

#include "meshmorph/app/case_file.h"
#include "meshmorph/io/mesh_io.h"

namespace meshmorph {
namespace {

const std::filesystem::path kExamples = std::filesystem::path(MESHMORPH_TEST_DATA) / ".." / ".." / "examples";

std::vector<std::string> example_names() {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(kExamples))
    if (std::filesystem::exists(entry.path() / "case.json")) names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

class Examples : public ::testing::TestWithParam<std::string> {};

TEST_P(Examples, CaseFileIsValidForItsMesh) {
  const CaseFile c = read_case_file(kExamples / GetParam() / "case.json");
  const Mesh mesh = read_mesh(c.mesh);
  EXPECT_NO_THROW(check_case_against_mesh(c, mesh));
  EXPECT_FALSE(c.boundary.empty());
  EXPECT_TRUE(c.output && c.report);
}

TEST_P(Examples, ReadmeOpensWithTheSampleRun) {
  std::ifstream in(kExamples / GetParam() / "README.md");
  std::string title, blank, sample;
  std::getline(in, title);
  std::getline(in, blank);
  std::getline(in, sample);
  EXPECT_EQ(title.rfind("# ", 0), 0u) << title;
  EXPECT_EQ(sample.rfind("Sample run: `build/bin/meshmorph ", 0), 0u) << sample;
  EXPECT_NE(sample.find("examples/" + GetParam() + "/case.json`"), std::string::npos) << sample;
}

INSTANTIATE_TEST_SUITE_P(All, Examples, ::testing::ValuesIn(example_names()),
                         [](const auto& p) { return "example_" + p.param.substr(0, 2); });

TEST(Examples, ThereAreAtLeastFour) { EXPECT_GE(example_names().size(), 4u); }

}  // namespace
}  // namespace meshmorph
