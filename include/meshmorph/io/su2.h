// SPDX-License-Identifier: MIT
#pragma once
#include <filesystem>
#include <ostream>
#include <string_view>

#include "meshmorph/mesh/mesh.h"

namespace meshmorph {

/// Reads an ASCII SU2 native mesh (.su2; su2code.github.io, "Mesh File"): NDIME= 2 or 3,
/// NELEM= with one element a line (its VTK type id — 5 triangle, 9 quadrilateral, 10
/// tetrahedron, 12 hexahedron, 13 prism, 14 pyramid —, its 0-based node ids in VTK's linear
/// order, an optional element index), NPOIN= (a second count, the domain points of a
/// partition, is allowed and ignored) with NDIME coordinates and an optional index a line,
/// NMARK= with MARKER_TAG= / MARKER_ELEMS= per marker (lines 3, triangles, quadrilaterals).
/// Sections may come in any order; '%' starts a comment; FFD_NBOX= ends the mesh (SU2_DEF's
/// free-form boxes are not read). Markers become facet groups named by their tags (tags 1, 2,
/// … in file order; a tag given twice joins its first group); cells carry no group. Nodes are
/// converted to the internal (Gmsh) order: VTK_WEDGE's base triangle faces away from its top,
/// Gmsh's towards it (vtk_cell_permutation). Throws InputError ("file: line N: …") for
/// malformed content, a multi-zone file (NZONE= above 1) and element types the format's
/// section does not hold; IoError when the file cannot be read.
Mesh read_su2(const std::filesystem::path& path);

/// read_su2 on the bytes of a file held in memory; `file` names it in messages.
Mesh parse_su2(std::string_view data, const std::filesystem::path& file);

/// Writes an ASCII SU2 mesh: NDIME, NELEM (cells with their index), NPOIN (coordinates, shortest
/// exact doubles, and the index), NMARK with one marker per group of dimension dim − 1 that
/// holds facets, in the order of Mesh::groups, named by the group (an unnamed group: "group_T"
/// for its tag T). Cells' groups, points and edges of a 3D mesh, untagged facets and node fields
/// are not written: the format holds none. Throws InputError for cells of order > 1 and for
/// a group name with white space or '%' (which SU2's MARKER_TAG cannot hold), before writing.
void write_su2(std::ostream& out, const Mesh& mesh);

}  // namespace meshmorph
