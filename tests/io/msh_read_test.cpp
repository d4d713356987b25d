// SPDX-License-Identifier: MIT
// MSH features that Gmsh files may have and our writer never produces.
#include "meshmorph/io/msh.h"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "meshmorph/io/mesh_io.h"

namespace meshmorph {
namespace {

namespace fs = std::filesystem;

fs::path write_file(const std::string& name, const std::string& text) {
  const fs::path dir = fs::temp_directory_path() / ("meshmorph_msh_read_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / name, std::ios::binary) << text;
  return dir / name;
}

// MSH 2.2 text with these $Nodes and $Elements lines.
std::string msh22(const std::vector<std::string>& nodes, const std::vector<std::string>& elements) {
  std::string text = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n" + std::to_string(nodes.size()) + "\n";
  for (const std::string& line : nodes) text += line + "\n";
  text += "$EndNodes\n$Elements\n" + std::to_string(elements.size()) + "\n";
  for (const std::string& line : elements) text += line + "\n";
  return text + "$EndElements\n";
}

// The unit square's corners, with sparse unordered tags.
const std::vector<std::string> k_square_nodes{"5 0 0 0", "6 1 0 0", "7 1 1 0", "9 0 1 0"};

// Unknown sections, a parametric node block, unordered sparse tags, an entity with two
// physical tags (the first one counts), elements in two blocks of one type.
TEST(MshRead, Gmsh41FeaturesBeyondWhatWeWrite) {
  const fs::path p = write_file("features.msh", R"($MeshFormat
4.1 0 8
$EndMeshFormat
$Comments
anything $Nodes here
$EndComments
$PhysicalNames
2
1 7 "wall"
2 3 "fluid domain"
$EndPhysicalNames
$Entities
0 1 2 0
4 0 0 0 1 0 0 1 7 0
1 0 0 0 1 1 0 2 3 9 0
2 0 0 0 1 1 0 0 0
$EndEntities
$Nodes
2 4 10 40
1 4 1 2
40
10
0 0 0 0
1 0 0 1
2 1 0 2
30
20
1 1 0
0 1 0
$EndNodes
$Elements
3 3 1 3
1 4 1 1
1 40 10
2 1 2 1
2 40 10 30
2 2 2 1
3 40 30 20
$EndElements
$Periodic
0
$EndPeriodic
)");
  const Mesh m = read_msh(p);
  EXPECT_EQ(m.dim, 2);
  EXPECT_EQ(m.node_tags, (std::vector<std::int64_t>{40, 10, 30, 20}));
  EXPECT_EQ(m.x(0, 1), 1.0);  // tag 10
  EXPECT_EQ(m.x(1, 2), 1.0);  // tag 30
  ASSERT_EQ(m.cells.size(), 1u);
  EXPECT_EQ(m.cells[0].nodes, (std::vector<std::int32_t>{0, 1, 2, 0, 2, 3}));
  EXPECT_EQ(m.cells[0].physical, (std::vector<std::int32_t>{3, 0}));
  EXPECT_EQ(m.cells[0].entity, (std::vector<std::int32_t>{1, 2}));
  ASSERT_EQ(m.facets.size(), 1u);
  EXPECT_EQ(m.facets[0].physical, (std::vector<std::int32_t>{7}));
  ASSERT_TRUE(m.find_group("fluid domain").has_value());
  EXPECT_EQ(m.find_group("fluid domain")->tag, 3);
  EXPECT_EQ(m.find_group("wall")->dim, 1);
}

TEST(MshRead, Msh22WithZeroOrManyTags) {
  const fs::path p = write_file("tags22.msh", msh22(k_square_nodes, {"1 2 0 5 6 7", "2 2 4 11 12 2 -3 5 7 9", "3 1 2 4 4 9 5"}));
  const Mesh m = read_mesh(p);
  ASSERT_EQ(m.cells.size(), 1u);
  EXPECT_EQ(m.cells[0].physical, (std::vector<std::int32_t>{0, 11}));
  EXPECT_EQ(m.cells[0].entity, (std::vector<std::int32_t>{0, 12}));
  EXPECT_EQ(m.cells[0].nodes, (std::vector<std::int32_t>{0, 1, 2, 0, 2, 3}));
  ASSERT_EQ(m.facets.size(), 1u);
  EXPECT_EQ(m.facets[0].physical, (std::vector<std::int32_t>{4}));
  // Unnamed groups come from the tags in use.
  ASSERT_EQ(m.groups.size(), 2u);
  EXPECT_EQ(m.groups[0].dim, 1);
  EXPECT_EQ(m.groups[0].tag, 4);
  EXPECT_EQ(m.groups[1].dim, 2);
  EXPECT_EQ(m.groups[1].tag, 11);
}

// MSH 2.2 writes a cell of several physical groups once per group: the mesh holds each cell
// once, where it first appears, with that line's tags.
TEST(MshRead, Msh22CellsRepeatedPerGroupAreKeptOnceWithTheirFirstTags) {
  std::vector<std::string> nodes = k_square_nodes;
  nodes.push_back("10 2 0 0");
  const fs::path p = write_file("repeats22.msh", msh22(nodes, {"1 2 2 11 1 5 6 7", "2 2 2 12 2 5 6 7", "3 2 2 11 3 5 7 9",
                                                              "4 2 2 11 4 6 10 7", "5 2 2 13 5 5 7 9", "6 2 2 14 6 6 10 7"}));
  const Mesh m = read_mesh(p);
  ASSERT_EQ(m.cells.size(), 1u);
  EXPECT_EQ(m.cells[0].nodes, (std::vector<std::int32_t>{0, 1, 2, 0, 2, 3, 1, 4, 2}));
  EXPECT_EQ(m.cells[0].physical, (std::vector<std::int32_t>{11, 11, 11}));
  EXPECT_EQ(m.cells[0].entity, (std::vector<std::int32_t>{1, 3, 4}));
}

TEST(MshRead, EntityTagsThatMixPhysicalTagsAreRenumberedOnWrite) {
  Mesh m;
  m.dim = 2;
  m.x.resize(2, 4);
  m.x << 0, 1, 1, 0, 0, 0, 1, 1;
  CellBlock b;
  b.nodes = {0, 1, 2, 0, 2, 3};
  b.physical = {1, 2};
  b.entity = {5, 5};  // one entity, two physical tags: MSH 4.1 cannot say that
  m.cells.push_back(b);
  for (const bool binary : {false, true}) {
    const fs::path p = write_file("mixed.msh", "");
    WriteOptions opt;
    opt.binary = binary;
    write_mesh(p, m, opt);
    const Mesh r = read_mesh(p);
    EXPECT_EQ(r.cells[0].physical, b.physical);
    EXPECT_NE(r.cells[0].entity[0], r.cells[0].entity[1]);
    EXPECT_EQ(r.node_tags, (std::vector<std::int64_t>{1, 2, 3, 4}));
  }
}

}  // namespace
}  // namespace meshmorph
