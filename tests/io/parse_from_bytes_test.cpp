// SPDX-License-Identifier: MIT
// parse_msh, parse_vtu and parse_medit: the readers on bytes held in memory (the fuzz targets'
// entry points) give the mesh that reading the file gives, and name the given file in errors.
#include <fstream>
#include <iterator>
#include <string>
#include <string_view>

#include <gtest/gtest.h>

#include "io/mesh_compare.h"
#include "meshmorph/error.h"
#include "meshmorph/io/medit.h"
#include "meshmorph/io/msh.h"
#include "meshmorph/io/vtu.h"

namespace meshmorph {
namespace {

std::string path(const std::string& name) { return std::string(MESHMORPH_TEST_DATA) + "/io/" + name; }

std::string bytes(const std::string& name) {
  std::ifstream in(path(name), std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::string error_of(auto&& parse) {
  try {
    parse();
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(ParseFromBytes, GivesTheMeshOfTheFile) {
  for (const char* name : {"gmsh_tri6_41a.msh", "gmsh_tri6_41b.msh", "gmsh_tri6_22b.msh", "gmsh_tri6_part3_41b.msh"}) {
    SCOPED_TRACE(name);
    test::expect_meshes_equal(parse_msh(bytes(name), name), read_msh(path(name)));
  }
  for (const char* name : {"meshio_tri6_ascii.vtu", "meshio_tri6_raw.vtu", "meshio_tri6_zlib.vtu"}) {
    SCOPED_TRACE(name);
    test::expect_meshes_equal(parse_vtu(bytes(name), name), read_vtu(path(name)));
  }
  test::expect_meshes_equal(parse_medit(bytes("meshio_tet4.mesh"), "m.mesh"), read_medit(path("meshio_tet4.mesh")));
}

TEST(ParseFromBytes, ErrorsNameTheGivenFile) {
  EXPECT_EQ(error_of([] { parse_msh("$MeshFormat\n4.0 0 8\n", "memory.msh"); }),
            "memory.msh: line 2: MSH 4.0 is not supported; save the mesh as MSH 4.1 or 2.2 (gmsh -format msh41)");
  EXPECT_EQ(error_of([] { parse_vtu("", "memory.vtu"); }), "memory.vtu: line 1: empty file");
  EXPECT_EQ(error_of([] { parse_medit("MeshVersionFormatted 2\nDimension 4\n", "memory.mesh"); }),
            "memory.mesh: line 2: Dimension must be 2 or 3");
}

TEST(ParseFromBytes, ReadsPastANulByte) {
  // The view's size bounds the input, not a terminating NUL: the NUL is the bad token.
  const std::string_view text("MeshVersionFormatted 2\nDimension \0 2\n", 37);
  EXPECT_EQ(error_of([&] { parse_medit(text, "nul.mesh"); }), "nul.mesh: line 2: expected dimension (an integer), got '?'");
}

}  // namespace
}  // namespace meshmorph
