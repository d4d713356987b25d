// SPDX-License-Identifier: MIT
// OpenFOAM polyMesh: folders written by OpenFOAM v1912 (tests/data/foam: channel_hex by
// blockMesh from its system/blockMeshDict, ASCII, and channel_hex_binary with `writeFormat
// binary`; hybrid_layer by gmshToFoam from tests/data/hybrid_layer.msh in MSH 2.2), the moved
// points written back into a time folder, and what is refused. OpenFOAM's own checkMesh on a
// morphed case is tests/io/foam_check_mesh.sh.
#include "meshmorph/io/foam.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <numeric>
#include <string>

#include "io/mesh_compare.h"
#include "meshmorph/error.h"
#include "meshmorph/fem/orientation.h"
#include "meshmorph/fem/structured.h"
#include "meshmorph/io/mesh_io.h"

namespace meshmorph {
namespace {

namespace fs = std::filesystem;

fs::path data(const std::string& name) { return fs::path(MESHMORPH_TEST_DATA) / "foam" / name; }

std::size_t count(const Mesh& m, ElementType type) {
  std::size_t n = 0;
  for (const auto* list : {&m.cells, &m.facets})
    for (const CellBlock& b : *list) n += b.type == type ? b.n_cells() : 0;
  return n;
}

std::size_t group_facets(const Mesh& m, const std::string& name) {
  const auto g = m.find_group(name);
  if (!g) return 0;
  std::size_t n = 0;
  for (const CellBlock& b : m.facets)
    n += static_cast<std::size_t>(std::count(b.physical.begin(), b.physical.end(), g->tag));
  return n;
}

void expect_positive_cells(const Mesh& m, double volume) {
  const std::vector<double> v = signed_volumes(m);
  EXPECT_GT(*std::min_element(v.begin(), v.end()), 0.0);
  EXPECT_NEAR(std::accumulate(v.begin(), v.end(), 0.0), volume, 1e-12 * volume);
}

std::string bytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// A copy of a fixture case in a scratch folder.
fs::path scratch_case(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("meshmorph_foam_" + std::to_string(::getpid())) / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  fs::copy(data(name), dir, fs::copy_options::recursive);
  return dir;
}

TEST(Foam, BlockMeshChannelOfHexahedra) {
  const Mesh m = read_mesh(data("channel_hex"));
  EXPECT_EQ(m.dim, 3);
  EXPECT_EQ(m.n_nodes(), 30u);
  EXPECT_EQ(count(m, ElementType::Hexahedron), 8u);
  expect_positive_cells(m, 0.2);
  // Node j is OpenFOAM's point j: the points file's order is kept.
  EXPECT_EQ(m.x.col(1), Eigen::Vector3d(0.5, 0, 0));
  EXPECT_EQ(m.x.col(15), Eigen::Vector3d(0, 0, 0.1));
  EXPECT_EQ(test::sorted_groups(m), (std::vector<std::tuple<int, int, std::string>>{
                                        {2, 1, "inlet"}, {2, 2, "outlet"}, {2, 3, "walls"}, {2, 4, "frontAndBack"}}));
  EXPECT_EQ(group_facets(m, "inlet"), 2u);
  EXPECT_EQ(group_facets(m, "walls"), 8u);
  EXPECT_EQ(group_facets(m, "frontAndBack"), 16u);  // an empty patch is a group like the others
}

TEST(Foam, EveryWayToNameTheMeshReadsTheSame) {
  const Mesh m = read_mesh(data("channel_hex"));
  test::expect_meshes_equal(read_mesh(data("channel_hex") / "constant" / "polyMesh"), m);
  // Binary labels and scalars; blockMesh's ASCII points are rounded to 6 digits.
  test::CompareOptions near;
  near.tolerance = 1e-15;
  test::expect_meshes_equal(read_mesh(data("channel_hex_binary")), m, near);
  const fs::path dir = scratch_case("channel_hex");
  std::ofstream(dir / "case.foam").close();
  test::expect_meshes_equal(read_mesh(dir / "case.foam"), m);
}

TEST(Foam, GmshToFoamHybridCellsOfEveryType) {
  const Mesh m = read_mesh(data("hybrid_layer"));
  EXPECT_EQ(count(m, ElementType::Hexahedron), 12u);  // as checkMesh counts them
  EXPECT_EQ(count(m, ElementType::Prism), 42u);
  EXPECT_EQ(count(m, ElementType::Pyramid), 4u);
  EXPECT_EQ(count(m, ElementType::Tetrahedron), 185u);
  expect_positive_cells(m, 2.0);
  EXPECT_EQ(group_facets(m, "bottom"), 18u);
  EXPECT_EQ(group_facets(m, "defaultFaces"), 138u);
  // gmshToFoam keeps Gmsh's nodes (printed to 6 digits) and the cells on them.
  const Mesh msh = read_mesh(fs::path(MESHMORPH_TEST_DATA) / "hybrid_layer.msh");
  ASSERT_EQ(msh.n_nodes(), m.n_nodes());
  EXPECT_LT((msh.x - m.x).cwiseAbs().maxCoeff(), 1e-9);
  const auto corner_sets = [](const Mesh& mesh) {
    std::vector<std::vector<std::int32_t>> sets;
    for (const CellBlock& b : mesh.cells)
      for (std::size_t c = 0; c < b.n_cells(); ++c) {
        std::vector<std::int32_t> s(b.cell(c), b.cell(c) + b.n_nodes_per_cell());
        std::sort(s.begin(), s.end());
        sets.push_back(s);
      }
    std::sort(sets.begin(), sets.end());
    return sets;
  };
  EXPECT_EQ(corner_sets(m), corner_sets(msh));
}

// A moved mesh goes back as <case>/<time>/polyMesh/points, bit for bit, the topology untouched.
TEST(Foam, MovedPointsRoundTripThroughATimeFolder) {
  const fs::path dir = scratch_case("hybrid_layer");
  Mesh m = read_mesh(dir);
  m.x += 1e-3 * Eigen::MatrixXd::Random(3, m.x.cols());
  const std::string faces = bytes(dir / "constant" / "polyMesh" / "faces");
  write_mesh(dir / "0.25", m);
  EXPECT_TRUE(fs::exists(dir / "0.25" / "polyMesh" / "points"));
  EXPECT_FALSE(fs::exists(dir / "0.25" / "polyMesh" / "faces"));
  EXPECT_EQ(bytes(dir / "constant" / "polyMesh" / "faces"), faces);
  const Mesh back = read_mesh(dir / "0.25");
  test::expect_meshes_equal(back, m);
  EXPECT_NE(bytes(dir / "0.25" / "polyMesh" / "points").find("location    \"0.25/polyMesh\";"), std::string::npos);
  // Written again from the time folder's mesh: the same file.
  write_mesh(dir / "0.5/", back);
  EXPECT_EQ(bytes(dir / "0.5" / "polyMesh" / "points"),
            bytes(dir / "0.25" / "polyMesh" / "points")
                .replace(bytes(dir / "0.25" / "polyMesh" / "points").find("0.25/"), 5, "0.5/"));
}

TEST(Foam, OnlyTheCasesOwnMeshGoesIntoItsTimeFolders) {
  const fs::path dir = scratch_case("channel_hex");
  try {
    write_mesh(dir / "0.1", structured_mesh(ElementType::Hexahedron, 1, 2));
    ADD_FAILURE() << "no exception";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("the mesh has 27 nodes (3D) where"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("has 30 points"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(dir / "0.1"));
  // The same nodes renumbered: the points file would not line up with the faces.
  Mesh renumbered = read_mesh(dir);
  renumbered.x.col(0).swap(renumbered.x.col(1));
  for (CellBlock& b : renumbered.cells)
    for (std::int32_t& v : b.nodes) v = v == 0 ? 1 : v == 1 ? 0 : v;
  try {
    write_mesh(dir / "0.1", renumbered);
    ADD_FAILURE() << "no exception";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("(another mesh, or its nodes renumbered)"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(dir / "0.1"));
  try {
    write_foam_points(dir / "later", read_mesh(dir));
    ADD_FAILURE() << "no exception";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("an OpenFOAM time folder is named by its time"), std::string::npos)
        << e.what();
  }
  EXPECT_FALSE(fs::exists(dir / "later"));
}

// Faces out of their owner and into their neighbour: a face turned over is named.
TEST(Foam, AFaceTurnedOverIsNamed) {
  const fs::path dir = scratch_case("channel_hex");
  const fs::path faces = dir / "constant" / "polyMesh" / "faces";
  std::string text = bytes(faces);
  const std::size_t at = text.find("4(1 6 21 16)");  // face 0, internal
  ASSERT_NE(at, std::string::npos);
  text.replace(at, 12, "4(16 21 6 1)");
  std::ofstream(faces, std::ios::binary | std::ios::trunc) << text;
  try {
    read_mesh(dir);
    ADD_FAILURE() << "no exception";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("face 0 is oriented against the other faces of cell"), std::string::npos)
        << e.what();
  }
}

// Every prefix of every file of a polyMesh, ASCII and binary, is an InputError naming the file
// and a line or byte offset, or (cut after the list's last ')') the same mesh.
TEST(Foam, EveryTruncationIsAnInputErrorNamingTheFile) {
  for (const std::string name : {"channel_hex", "channel_hex_binary"}) {
    const fs::path dir = scratch_case(name);
    const Mesh whole = read_mesh(dir);
    for (const char* file : {"points", "faces", "owner", "neighbour", "boundary"}) {
      SCOPED_TRACE(name + "/" + file);
      const fs::path path = dir / "constant" / "polyMesh" / file;
      const std::string full = bytes(path);
      const std::size_t stride = std::max<std::size_t>(1, full.size() / 40);
      int errors = 0;
      for (std::size_t n = 0; n < full.size(); n += stride) {
        std::ofstream(path, std::ios::binary | std::ios::trunc) << full.substr(0, n);
        try {
          test::expect_meshes_equal(read_mesh(dir), whole);
          EXPECT_GT(n, full.rfind(')')) << "a prefix of " << n << " bytes was accepted";
        } catch (const InputError& e) {
          ++errors;
          const std::string msg = e.what();
          EXPECT_TRUE(msg.find(path.string() + ": line ") == 0 || msg.find(path.string() + ": byte offset ") == 0)
              << n << ": " << msg;
        }
      }
      EXPECT_GT(errors, 25);
      std::ofstream(path, std::ios::binary | std::ios::trunc) << full;
    }
  }
}

TEST(Foam, AFolderWithoutPolyMeshIsNamed) {
  const fs::path dir = fs::temp_directory_path() / ("meshmorph_foam_empty_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  EXPECT_THROW(read_mesh(dir), InputError);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace meshmorph
