// SPDX-License-Identifier: MIT
#include "meshmorph/io/cgns.h"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <gtest/gtest.h>

#include "meshmorph/error.h"
#include "meshmorph/fem/structured.h"
#include "meshmorph/io/exodus.h"
#include "meshmorph/io/mesh_io.h"

namespace meshmorph {
namespace {

namespace fs = std::filesystem;

// Two zones of a hexahedron each, meeting on z = 1, as other tools write them (a MIXED
// section, an ElementRange BC of family "Floor", a Vertex BC "lid"; tests/data/io): one mesh
// of 12 nodes, the interface's nodes merged, the BCs as groups.
TEST(Cgns, ConformingZonesMergeAndBcsBecomeGroups) {
  const Mesh m = read_cgns(fs::path(MESHMORPH_TEST_DATA) / "io" / "cgns_two_zones.cgns");
  EXPECT_EQ(m.dim, 3);
  EXPECT_EQ(m.n_nodes(), 12u);
  ASSERT_EQ(m.cells.size(), 1u);
  EXPECT_EQ(m.cells[0].nodes, (std::vector<std::int32_t>{0, 1, 2, 3, 4, 5, 6, 7, 4, 5, 6, 7, 8, 9, 10, 11}));
  ASSERT_EQ(m.facets.size(), 1u);
  EXPECT_EQ(m.facets[0].nodes, (std::vector<std::int32_t>{0, 3, 2, 1, 8, 9, 10, 11}));
  EXPECT_EQ(m.facets[0].physical, (std::vector<std::int32_t>{1, 2}));
  ASSERT_EQ(m.groups.size(), 2u);
  EXPECT_EQ(m.groups[0].name, "Floor");
  EXPECT_EQ(m.groups[1].name, "lid");
  EXPECT_EQ(m.groups[1].dim, 2);
}

// Every prefix of a written file is an InputError naming the file and a position (a CGNS
// node, an Exodus block, set, the coordinates or the header), or the whole mesh; never a
// crash, a message from the libraries or another exception.
// A file of the CGNS project's own tools (tecplot_to_cgns, tests/data/io/independent_cgns.sh)
// from the tetrahedra of a Gmsh mesh: the same nodes (the tool stores them as RealSingle) and
// the same cells.
TEST(Cgns, ReadsWhatTheCgnsToolsWrite) {
  const fs::path dir = fs::path(MESHMORPH_TEST_DATA) / "io";
  const Mesh m = read_cgns(dir / "tecplot_to_cgns_tet4.cgns");
  const Mesh gmsh = read_mesh(dir / "gmsh_tet4_22a.msh");
  ASSERT_EQ(m.n_nodes(), gmsh.n_nodes());
  EXPECT_LT((m.x - gmsh.x).cwiseAbs().maxCoeff(), 1e-7);
  EXPECT_GT((m.x - gmsh.x).cwiseAbs().maxCoeff(), 0.0);  // single precision indeed: read as written
  ASSERT_EQ(m.cells.size(), 1u);
  ASSERT_EQ(gmsh.cells.size(), 1u);
  EXPECT_EQ(m.cells[0].type, ElementType::Tetrahedron);
  EXPECT_EQ(m.cells[0].nodes, gmsh.cells[0].nodes);
}

TEST(Cgns, EveryTruncationOfCgnsAndExodusIsAnInputError) {
  const fs::path dir = fs::temp_directory_path() / ("meshmorph_cgns_cut_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const Mesh m = structured_mesh(ElementType::Hexahedron, 2, 1);
  for (const char* name : {"full.cgns", "full.exo"}) {
    SCOPED_TRACE(name);
    write_mesh(dir / name, m);
    std::ifstream in(dir / name, std::ios::binary);
    const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    const fs::path cut = dir / (std::string("cut") + fs::path(name).extension().string());
    for (std::size_t n = 0; n < bytes.size(); n += bytes.size() / 40) {
      std::ofstream(cut, std::ios::binary | std::ios::trunc).write(bytes.data(), static_cast<std::streamsize>(n));
      try {
        read_mesh(cut);
        ADD_FAILURE() << "a prefix of " << n << " bytes was accepted";
      } catch (const InputError& e) {
        const std::string msg = e.what();
        EXPECT_EQ(msg.rfind(cut.string() + ": ", 0), 0u) << msg;
      } catch (const std::exception& e) {
        ADD_FAILURE() << "not an InputError at " << n << " bytes: " << e.what();
      }
    }
  }
  fs::remove_all(dir);
}

TEST(Cgns, FolderAndMissingFileAreIoErrors) {
  EXPECT_THROW(read_cgns(fs::path(MESHMORPH_TEST_DATA) / "io" / "missing.cgns"), IoError);
  EXPECT_THROW(read_exodus(fs::path(MESHMORPH_TEST_DATA) / "io" / "missing.exo"), IoError);
  EXPECT_THROW(read_mesh(fs::path(MESHMORPH_TEST_DATA) / "io"), InputError);  // (no extension)
}

}  // namespace
}  // namespace meshmorph
