// SPDX-License-Identifier: MIT
#pragma once
#include <filesystem>

#include "meshmorph/mesh/mesh.h"

namespace meshmorph {

/// Reads an Exodus II file (netCDF): coordinates, element blocks of the types of
/// exodus_type_order in the internal node order, side sets as facets (each (element, side)
/// pair the side's nodes, sides numbered as exodus_sides) and node sets as points, all as
/// groups named by ex_get_names. A block's group tag is its property GROUP where it has one
/// (meshmorph writes it), else its id; side and node sets take their ids. Blocks of lower
/// dimension than the mesh are facets. Malformed or unsupported content is an InputError
/// "file: element block 3: what" (side set, node set, coordinates, header).
Mesh read_exodus(const std::filesystem::path& path);

/// Writes `mesh` as Exodus II (double precision) at `file`, a temporary path the caller
/// renames (`shown`, the final path, is the file named in IoError messages): an element
/// block per cell type, order and group (ids 1, 2, …; named after its group, property GROUP
/// = its tag), facets of dimension dim − 1 as side sets (id = tag, name = group name), point
/// facets as node sets, lines of a 3D mesh as element blocks. Facets of no group, or on no
/// cell's side, are not written. Throws InputError without the file name for what Exodus
/// cannot hold (cells of order 3 or 4, names over 32 characters), IoError when the library
/// fails.
void write_exodus(const std::filesystem::path& file, const Mesh& mesh, const std::filesystem::path& shown);

}  // namespace meshmorph
