// SPDX-License-Identifier: MIT
#pragma once
#include <filesystem>
#include <ostream>
#include <string_view>

#include "meshmorph/mesh/mesh.h"

namespace meshmorph {

/// Reads an ASCII Medit .mesh file (INRIA GMF): Dimension, Vertices (x y [z] ref),
/// Edges, Triangles, Quadrilaterals, Tetrahedra, Hexahedra (also spelled Hexaedra), Prisms,
/// Pyramids (their vertices in Gmsh's order, as meshio reads them), End;
/// the flag keywords Corners, Ridges, RequiredVertices, RequiredEdges, RequiredTriangles
/// are skipped. Indices are 1-based; element references become physical tags (unnamed
/// groups); vertex references are ignored. The mesh has no node fields (Medit keeps
/// solutions in separate .sol files, which are not read). Curved (P2…) keywords and other
/// keywords are an InputError ("file: line N: …").
Mesh read_medit(const std::filesystem::path& path);

/// read_medit on the bytes of a file held in memory; `file` names it in messages.
Mesh parse_medit(std::string_view data, const std::filesystem::path& file);

/// Writes an ASCII Medit .mesh file (MeshVersionFormatted 2): vertices (the reference is
/// the physical tag of a Point facet on the node, else 0), then facets and cells with
/// their physical tags as references. Node fields are not written. Throws InputError for
/// cells of order > 1.
void write_medit(std::ostream& out, const Mesh& mesh);

}  // namespace meshmorph
