// SPDX-License-Identifier: MIT
#include <gtest/gtest.h>

#include "app/temp_dir.h"
#include "meshmorph/app/case_file.h"
#include "meshmorph/error.h"

namespace meshmorph {
namespace {

std::string error_of(const std::filesystem::path& p) {
  try {
    read_displacement_csv(p);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(DisplacementCsv, ReadsHeaderAndThreeComponents) {
  test::TempDir dir;
  const auto p = dir.write("d.csv", "node, dx, dy, dz\r\n\n 12 ,1.5,-2,3e-3\n7,0,0,+1\n");
  const DisplacementTable t = read_displacement_csv(p);
  EXPECT_EQ(t.file, p);
  EXPECT_EQ(t.node_tags, (std::vector<std::int64_t>{12, 7}));
  EXPECT_EQ(t.line, (std::vector<int>{3, 4}));
  ASSERT_EQ(t.displacement.rows(), 3);
  ASSERT_EQ(t.displacement.cols(), 2);
  EXPECT_EQ(t.displacement(0, 0), 1.5);
  EXPECT_EQ(t.displacement(1, 0), -2.0);
  EXPECT_EQ(t.displacement(2, 0), 3e-3);
  EXPECT_EQ(t.displacement(2, 1), 1.0);
}

TEST(DisplacementCsv, ReadsTwoComponentsWithoutHeader) {
  test::TempDir dir;
  const DisplacementTable t = read_displacement_csv(dir.write("d.csv", "1,0.25,0.5\n2,-1,1"));
  EXPECT_EQ(t.node_tags, (std::vector<std::int64_t>{1, 2}));
  EXPECT_EQ(t.displacement.rows(), 2);
  EXPECT_EQ(t.displacement(1, 1), 1.0);
}

TEST(DisplacementCsv, ErrorsNameFileAndLine) {
  test::TempDir dir;
  const struct {
    const char* text;
    const char* expected;
  } cases[] = {
      {"node,dx,dy\n1,0,0\n2,x,0\n", ":3: field 2: expected a number, found \"x\""},
      {"1,0,0\n2,nan,0\n", ":2: field 2: expected a finite number"},
      {"1,0,inf\n", ":1: field 3: expected a finite number"},
      {"1,0,0\n1,1,1\n", ":2: node 1 is listed twice"},
      {"1,0,0\n2,0,0,0\n", ":2: expected 3 fields like the first row, found 4"},
      {"1,0\n", ":1: expected node,dx,dy or node,dx,dy,dz, found 2 fields"},
      {"1,0,0\n0,0,0\n", ":2: node numbers start at 1, found 0"},
      {"h\n1,0,0\nabc,0,0\n", ":3: expected a node number, found \"abc\""},
      {"1,0,0\n1.5,0,0\n", ":2: expected a node number, found \"1.5\""},
      {"node,dx,dy\n\n", ":1: no displacement rows"},
      {"", ":1: no displacement rows"},
  };
  for (const auto& c : cases) {
    const auto p = dir.write("bad.csv", c.text);
    const std::string e = error_of(p);
    EXPECT_EQ(e.rfind(p.string() + ":", 0), 0u) << e;
    EXPECT_NE(e.find(c.expected), std::string::npos) << "csv: " << c.text << "\nmessage: " << e;
  }
}

TEST(DisplacementCsv, MissingFileIsAnIoError) {
  test::TempDir dir;
  EXPECT_THROW(read_displacement_csv(dir.path() / "none.csv"), IoError);
}

}  // namespace
}  // namespace meshmorph
