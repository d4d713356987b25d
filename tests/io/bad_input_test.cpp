// SPDX-License-Identifier: MIT
// Every file in tests/data/bad is malformed: reading it throws InputError whose message names
// the file and a line ("file: line N: …") or byte offset ("file: byte offset N: …") and says
// what is wrong. The CLI tests reuse the folder (exit code 2 for `meshmorph convert`).
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <regex>
#include <string>

#include <gtest/gtest.h>

#include "meshmorph/error.h"
#include "meshmorph/fem/structured.h"
#include "meshmorph/io/mesh_io.h"

namespace meshmorph {
namespace {

namespace fs = std::filesystem;

// What each message must say (a fragment), so that a file fails for the intended reason.
const std::map<std::string, std::string>& expected_reasons() {
  static const std::map<std::string, std::string> m{
      {"cgns_bc_element_in_no_section.cgns", "node /Base/Zone/ZoneBC/wall: element 99 is in no element section"},
      {"cgns_degenerate_element.cgns", "node /Base/Zone/Hexa: element 1 lists node 6 twice (a degenerate element)"},
      {"cgns_nan_coordinate.cgns", "node /Base/Zone/GridCoordinates/CoordinateY: node 6 has a non-finite coordinate"},
      {"cgns_node_out_of_range.cgns", "node /Base/Zone/Hexa: element 1 references node 9, outside 1..8"},
      {"cgns_nonconforming_zones.cgns", "node /Base: the zones do not conform"},
      {"cgns_not_cgns.cgns", "node /: not a CGNS file"},
      {"cgns_serendipity_quad8.cgns", "node /Base/Zone/Serendipity: element 2: unsupported CGNS element type QUAD_8"},
      {"cgns_structured_zone.cgns", "node /Base/Block: structured zones are not supported"},
      {"cgns_two_bases.cgns", "node /: holds 2 bases"},
      {"exodus_degenerate_element.exo", "element block 1: element 1 lists node 2 twice (a degenerate element)"},
      {"exodus_nan_coordinate.exo", "coordinates: node 4 has a non-finite coordinate"},
      {"exodus_node_out_of_range.exo", "element block 1: element 1 references node 40, outside 1..8"},
      {"exodus_not_netcdf.exo", "header: not an Exodus II (netCDF) file"},
      {"exodus_serendipity_hex20.exo", "element block 1: unsupported element type 'HEX20' with 20 nodes"},
      {"exodus_shell_element.exo", "element block 1: unsupported element type 'SHELL4' with 4 nodes"},
      {"exodus_side_out_of_range.exo", "side set 1: entry 1: side 7 of element 1 (a hexahedron) is not among its 6 sides"},
      {"exodus_side_set_element_out_of_range.exo", "side set 1: entry 1 names element 2, outside 1..1"},
      {"medit_bad_coordinate.mesh", "line 7: expected coordinate (a number), got '1e999'"},
      {"medit_bad_dimension.mesh", "line 2: Dimension must be 2 or 3"},
      {"medit_curved_triangles.mesh", "line 9: curved Medit elements"},
      {"medit_degenerate_triangle.mesh", "line 12: element lists vertex 3 twice (a degenerate element)"},
      {"medit_missing_count.mesh", "line 4: expected number of vertices"},
      {"medit_no_cells.mesh", "line 7: no triangle, quadrilateral, tetrahedron or hexahedron cells"},
      {"medit_truncated.mesh", "unexpected end of file"},
      {"medit_unknown_keyword.mesh", "line 9: unknown or unsupported Medit keyword 'Pentagons'"},
      {"medit_vertex_index_too_large.mesh", "line 12: vertex index 5 is outside 1..4"},
      {"medit_vertex_index_zero.mesh", "line 12: vertex index 0 is outside 1..4"},
      {"msh22_bad_number.msh", "line 8: expected z coordinate (a number), got 'x'"},
      {"msh22_bad_tag_count.msh", "line 13: number of tags must be 0..1000"},
      {"msh22_degenerate_element.msh", "line 14: element lists node tag 4 twice (a degenerate element)"},
      {"msh22_node_data_truncated.msh", "line 28: expected node tag (an integer), got '$EndNodeData'"},
      {"msh22_binary_cut.msh", "byte offset"},
      {"msh22_binary_cut_elements.msh", "byte offset"},
      {"msh22_binary_element_type_minus1.msh", "byte offset 184: unsupported element type -1"},
      {"msh22_element_type_minus1.msh", "line 13: unsupported element type -1"},
      {"msh22_pyramid13.msh", "line 13: element lists node tag 1 twice (a degenerate element)"},
      {"msh22_truncated.msh", "line 12: count 2 is larger than the rest of the file can hold"},
      {"msh22_wrong_element_count.msh", "expected element tag"},
      {"msh40_header.msh", "line 2: MSH 4.0 is not supported"},
      {"msh41_bad_number.msh", "line 16: expected y coordinate (a number), got '0.5.3'"},
      {"msh41_binary_cut.msh", "byte offset"},
      {"msh41_binary_element_type_1000.msh", "byte offset 10030: unsupported element type 1000"},
      {"msh41_binary_endianness.msh", "byte offset 20: binary MSH with a foreign byte order"},
      {"msh41_degenerate_element.msh", "line 24: element lists node tag 3 twice (a degenerate element)"},
      {"msh41_duplicate_node_tag.msh", "duplicate node tag 3"},
      {"msh41_elements_before_nodes.msh", "line 8: $Elements before $Nodes"},
      {"msh41_huge_node_count.msh", "count 99999999999 is larger than the rest of the file"},
      {"msh41_inf_coordinate.msh", "line 17: x coordinate is not finite"},
      {"msh41_missing_endnodes.msh", "expected $EndNodes, got '$Elements'"},
      {"msh41_nan_coordinate.msh", "line 16: y coordinate is not finite"},
      {"msh41_negative_count.msh", "expected number of nodes (an integer), got '-4'"},
      {"msh41_node_data_binary_cut.msh", "byte offset 572: unexpected end of file in binary data, expected field value"},
      {"msh41_node_data_missing_value.msh", "line 26: $NodeData \"phi\" (time step 0) has no value for node tag 3"},
      {"msh41_node_data_undefined_tag.msh", "line 37: $NodeData \"phi\" gives a value to undefined node tag 9"},
      {"msh41_no_cells.msh", "no triangle, quadrilateral, tetrahedron or hexahedron cells"},
      {"msh41_empty_cell_block.msh", "line 22: no triangle, quadrilateral, tetrahedron or hexahedron cells"},
      {"msh41_nonzero_z_without_3d_cells.msh", "line 17: node has z != 0"},
      {"msh41_physical_name_control_byte.msh", "line 6: physical name holds the control byte 0x01 at byte 3"},
      {"msh41_physical_name_invalid_utf8.msh", "line 6: physical name is not valid UTF-8 (byte 0xff at byte 3)"},
      {"msh41_physical_name_missing_quote.msh", "line 6: missing closing quote"},
      {"msh41_serendipity_quad12.msh", "line 38: serendipity/incomplete element type 39 (QUA_12)"},
      {"msh41_too_few_element_nodes.msh", "expected node tag (an integer), got '$EndElements'"},
      {"msh41_truncated.msh", "line 13: count 4 is larger than the rest of the file can hold"},
      {"msh41_undefined_node_tag.msh", "line 24: element references undefined node tag 9"},
      {"msh41_unknown_element_type.msh", "unsupported element type 200"},
      {"msh41_unterminated_section.msh", "section $Comments has no $EndComments"},
      {"msh41_wrong_node_count.msh", "announced 5 nodes but the blocks hold 4"},
      {"msh_empty.msh", "line 1: empty file"},
      {"msh_not_gmsh.msh", "line 1: expected $MeshFormat, got 'solid'"},
      {"msh_version_3.msh", "unsupported MSH version '3.0'"},
      {"su2_bad_coordinate.su2", "line 6: expected coordinate (a number), got 'x'"},
      {"su2_degenerate_element.su2", "line 3: element lists node 1 twice (a degenerate element)"},
      {"su2_extra_token.su2", "line 3: unexpected '7' after the element's nodes"},
      {"su2_missing_marker_elems.su2", "line 10: expected MARKER_ELEMS= after MARKER_TAG="},
      {"su2_multizone.su2", "line 2: multi-zone SU2 files (NZONE= 2) are not supported"},
      {"su2_no_points.su2", "line 4: no NPOIN= section"},
      {"su2_node_id_too_large.su2", "line 4: node id 9 is outside 0..3 (NPOIN= 4)"},
      {"su2_too_few_element_nodes.su2", "line 4: element type 5 has 3 nodes, the line holds 2"},
      {"su2_triangle_marker_in_2d.su2", "line 11: element type 5 is not a marker facet of a 2D SU2 mesh (expected 3 (line))"},
      {"su2_truncated_elements.su2", "line 4: NELEM= announces 4 elements, the section holds 1"},
      {"su2_unknown_element_type.su2", "line 4: element type 7 is not a cell of a 2D SU2 mesh"},
      {"su2_unknown_keyword.su2", "line 8: unknown SU2 keyword 'NBOX='"},
      {"foam_binary_points_cut", "polyMesh/points: line 20: the binary list of 30 points is cut short"},
      {"foam_cell_label_too_large", "polyMesh/owner: line 20: cell 99999 (in owner or neighbour) is beyond the 19 cells"},
      {"foam_face_turned_over", "polyMesh: face 1 is oriented against the other faces of cell 0"},
      {"foam_negative_neighbour", "polyMesh/neighbour: line 19: neighbour cell -4 is negative"},
      {"foam_no_header", "polyMesh/points: line 11: expected the FoamFile header, got '30'"},
      {"foam_owner_too_short", "polyMesh/owner: line 20: the owner list holds 37 cells for 38 faces"},
      {"foam_patch_gap", "polyMesh/boundary: line 32: patch 'walls' holds faces 15..22; the next boundary faces are 14..37"},
      {"foam_point_label_too_large", "polyMesh/faces: line 23: point label 99 is outside the points 0..29"},
      {"foam_polyhedron", "polyMesh: cell 0 has 7 faces (2 triangles, 5 quadrilaterals, 0 of more points)"},
      {"foam_unclosed_cell", "polyMesh: cell 1: its faces do not close a hexahedron"},
      {"vtu_bad_xml.vtu", "XML error"},
      {"vtu_group_name_control_byte.vtu", "line 5: group name holds the control byte 0x01 at byte 3"},
      {"vtu_no_cells.vtu", "line 16: no triangle, quadrilateral, tetrahedron or hexahedron cells"},
      {"vtu_base64_garbage.vtu", "invalid base64"},
      {"vtu_degenerate_cell.vtu", "cell 1 lists point 3 twice (a degenerate cell)"},
      {"vtu_empty.vtu", "line 1: empty file"},
      {"vtu_index_out_of_range.vtu", "connectivity index 4 is out of range"},
      {"vtu_missing_connectivity.vtu", "Cells needs DataArrays 'connectivity', 'offsets' and 'types'"},
      {"vtu_nan_point.vtu", "non-finite value"},
      {"vtu_not_unstructured_grid.vtu", "VTKFile type must be UnstructuredGrid"},
      {"vtu_offsets_decreasing.vtu", "offsets do not match the connectivity (cell 1)"},
      {"vtu_offsets_not_matching.vtu", "offsets do not match the connectivity (cell 1)"},
      {"vtu_point_data_wrong_count.vtu", "line 16: DataArray 'phi' holds 3 values, expected 4"},
      {"vtu_points_two_components.vtu", "Points must have 3 components"},
      {"vtu_biquadratic_triangle.vtu", "unsupported VTK cell type 34"},
      {"vtu_quadratic_wedge_14_points.vtu", "cell 0 of VTK type 26 has 14 points, not 15"},
      {"vtu_too_few_points.vtu", "holds 9 values, expected 12"},
      {"vtu_unknown_cell_type.vtu", "unsupported VTK cell type 42 (cell 1)"},
      {"vtu_wrong_lagrange_point_count.vtu", "has 7 points, which is no complete Lagrange cell"},
      {"vtu_zlib_block_size_4GB.vtu", "line 6: DataArray 'Points' block 0 announces 4294967280 bytes"},
      {"vtu_zlib_last_size_2e40.vtu", "line 6: DataArray 'Points' block 0 announces 1099511627776 bytes"},
  };
  return m;
}

TEST(BadInput, EveryFileGivesInputErrorNamingFileAndPosition) {
  const fs::path dir = fs::path(MESHMORPH_TEST_DATA) / "bad";
  int n = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    SCOPED_TRACE(name);
    ++n;
    try {
      read_mesh(entry.path());
      ADD_FAILURE() << "no exception";
    } catch (const InputError& e) {
      const std::string msg = e.what();
      EXPECT_NE(msg.find(name), std::string::npos) << msg;
      // An OpenFOAM case (a folder) is named with its file and line, or its polyMesh folder and
      // a cell or face; CGNS and Exodus II files, read through their libraries, with a CGNS node
      // path, or an Exodus block, set, the coordinates or the header.
      const bool case_position =
          entry.is_directory() &&
          std::regex_search(msg, std::regex(name + "/constant/polyMesh(/[a-z]+: line|: cell|: face) [0-9]+"));
      bool at = msg.find(name + ": line ") != std::string::npos || msg.find(name + ": byte offset ") != std::string::npos ||
                msg.find(name + ": node /") != std::string::npos || case_position;
      for (const char* where : {": element block ", ": side set ", ": node set ", ": coordinates: ", ": header: "})
        at = at || msg.find(name + where) != std::string::npos;
      EXPECT_TRUE(at) << msg;
      const auto it = expected_reasons().find(name);
      ASSERT_NE(it, expected_reasons().end()) << "add the expected reason of " << name << ": " << msg;
      EXPECT_NE(msg.find(it->second), std::string::npos) << msg;
    } catch (const std::exception& e) {
      ADD_FAILURE() << "not an InputError: " << e.what();
    }
  }
  EXPECT_EQ(n, static_cast<int>(expected_reasons().size()));
}

TEST(BadInput, UnknownExtensionAndMissingFile) {
  EXPECT_THROW(read_mesh("mesh.stl"), InputError);
  EXPECT_THROW(read_mesh(fs::path(MESHMORPH_TEST_DATA) / "bad" / "does_not_exist.msh"), IoError);
}

// A folder opens as a stream whose size is LLONG_MAX: reading it must not end in std::bad_alloc.
TEST(BadInput, FolderIsAnIoErrorNamingIt) {
  const fs::path dir = fs::temp_directory_path() / ("meshmorph_folder_" + std::to_string(::getpid()));
  for (const char* name : {"a.msh", "a.vtu", "a.mesh"}) {
    SCOPED_TRACE(name);
    fs::create_directories(dir / name);
    try {
      read_mesh(dir / name);
      ADD_FAILURE() << "no exception";
    } catch (const IoError& e) {
      EXPECT_EQ(std::string(e.what()), (dir / name).string() + ": is a folder, not a mesh file");
    } catch (const std::exception& e) {
      ADD_FAILURE() << "not an IoError: " << e.what();
    }
  }
  fs::remove_all(dir);
}

// Every prefix of a valid file is either an InputError naming a position or (Medit, whose
// End keyword is optional) a valid mesh; never a crash or another exception.
TEST(BadInput, EveryTruncationIsAnInputError) {
  const fs::path dir = fs::temp_directory_path() / ("meshmorph_truncate_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  Mesh m = structured_mesh(ElementType::Quadrilateral, 2, 1);
  m.node_fields["phi"] = m.x.row(0).transpose() / 3.0;  // cuts inside $NodeData and PointData too
  const Mesh linear = structured_mesh(ElementType::Tetrahedron, 1, 1);
  struct Variant {
    const char* name;
    MeshFormat format;
    bool binary;
  };
  for (const Variant v : {Variant{"a41.msh", MeshFormat::Msh41, false}, Variant{"b41.msh", MeshFormat::Msh41, true},
                          Variant{"a22.msh", MeshFormat::Msh22, false}, Variant{"b22.msh", MeshFormat::Msh22, true},
                          Variant{"a.vtu", MeshFormat::Vtu, false}, Variant{"b.vtu", MeshFormat::Vtu, true},
                          Variant{"m.mesh", MeshFormat::Medit, false}}) {
    SCOPED_TRACE(v.name);
    const fs::path full = dir / (std::string("full_") + v.name);
    write_mesh(full, v.format == MeshFormat::Medit ? linear : m, {v.format, v.binary, {}, {}});
    std::ifstream in(full, std::ios::binary);
    const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    const fs::path cut = dir / v.name;
    int errors = 0;
    // About 100 cut points per file (file I/O dominates), plus every cut near the end.
    const std::size_t stride = std::max<std::size_t>(1, bytes.size() / 100);
    int cuts = 0;
    for (std::size_t n = 0; n < bytes.size(); n += (n + 40 >= bytes.size() ? 1 : stride)) {
      ++cuts;
      std::ofstream(cut, std::ios::binary | std::ios::trunc).write(bytes.data(), static_cast<std::streamsize>(n));
      try {
        const Mesh r = read_mesh(cut);
        const bool only_space_cut = bytes.find_first_not_of(" \n", n) == std::string::npos;
        // Cut between $EndElements and $NodeData: a complete mesh without node data.
        const std::string head = bytes.substr(0, bytes.find_last_not_of(" \n", n == 0 ? 0 : n - 1) + 1);
        const bool section_cut = head.ends_with("$EndElements") && r.node_fields.empty();
        EXPECT_TRUE(v.format == MeshFormat::Medit || only_space_cut || section_cut)
            << "a prefix of " << n << " bytes was accepted";
      } catch (const InputError& e) {
        const std::string msg = e.what();
        ++errors;
        if (msg.find(": line ") == std::string::npos && msg.find(": byte offset ") == std::string::npos)
          ADD_FAILURE() << "no position at " << n << " bytes: " << msg;
      } catch (const std::exception& e) {
        ADD_FAILURE() << "not an InputError at " << n << " bytes: " << e.what();
      }
    }
    EXPECT_GT(errors, cuts / 2);
    EXPECT_NO_THROW(read_mesh(full));
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace meshmorph
