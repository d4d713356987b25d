// SPDX-License-Identifier: MIT
#pragma once
#include <filesystem>
#include <map>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "meshmorph/mesh/mesh.h"

namespace meshmorph {

/// Reads a VTK XML unstructured grid (.vtu): ascii, base64 "binary" and appended (raw or
/// base64) arrays, zlib-compressed or not, UInt32 or UInt64 headers, any number of pieces.
/// Cells: vertex 1, line 3, triangle 5, quad 9, tetra 10, hexahedron 12, the quadratic
/// types 21, 22, 24, 28, 29 and the Lagrange types 68–72 (order from the point count,
/// 1–4); nodes are permuted to the internal (Gmsh) ordering. Cells of the highest
/// dimension become Mesh::cells, the others facets. A cell array named `group`,
/// `material`, `attribute` or `gmsh:physical` gives the physical tags, `entity` or
/// `gmsh:geometrical` the entity tags; integer FieldData arrays of two values (tag, dim)
/// name the groups. Named scalar PointData arrays (NumberOfComponents absent or 1, any
/// numeric type and encoding; NaN allowed) become Mesh::node_fields; arrays of several
/// components, String and Bit arrays are skipped. With several pieces, each must have the
/// same scalar arrays. Node tags are 1..n. Throws InputError ("file: line N: …") for malformed content.
Mesh read_vtu(const std::filesystem::path& path);

/// read_vtu on the bytes of a file held in memory; `file` names it in messages.
Mesh parse_vtu(std::string_view data, const std::filesystem::path& file);

/// Writes a .vtu file (little-endian, UInt64 headers; `version="2.2"` when Lagrange
/// hexahedra are present, as VTK does, else "1.0"): Points as Float64 with 3 components,
/// cells then facets, linear ones as VTK's classic types (1, 3, 5, 9, 10, 12, 13 wedge, 14
/// pyramid), higher orders as Lagrange cells (68–73) in VTK's node ordering (the classic
/// wedge's own: vtk_cell_permutation), Mesh::node_fields as Float64
/// PointData, cell data Int32 `group` (physical tag) and `entity`, each array of
/// `cell_data` as Float64 (one value per cell of Mesh::cells; NaN on facets), and named
/// groups as FieldData arrays {tag, dim}. `binary`: base64-encoded arrays, else ASCII with
/// shortest exact doubles. Throws std::invalid_argument if a cell_data array or a node
/// field has the wrong length, InputError for pyramids of order 2 (VTK 9.1 cannot read them).
/// Each of `point_vectors` (Mesh::dim × n_nodes) is a Float64 PointData array of 3 components.
void write_vtu(std::ostream& out, const Mesh& mesh, bool binary,
               const std::map<std::string, std::vector<double>>& cell_data = {},
               const std::map<std::string, Eigen::MatrixXd>& point_vectors = {});

}  // namespace meshmorph
