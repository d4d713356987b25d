// SPDX-License-Identifier: MIT
#pragma once
#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "meshmorph/io/mesh_series.h"
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
/// cell's side, are not written. Fields, where there are any, at one time step (time 0):
/// each of `point_vectors` (Mesh::dim × n_nodes) as the nodal variables <name>_x/_y(/_z) but
/// `displacement` (an Exodus displacement is added to the coordinates, which are already the
/// moved ones), each of `cell_data` (one value per cell of Mesh::cells) as an element variable
/// of the cell blocks. Throws InputError without the file name for what Exodus cannot hold
/// (cells of order 3 or 4, names over 32 characters), IoError when the library fails.
void write_exodus(const std::filesystem::path& file, const Mesh& mesh, const std::filesystem::path& shown,
                  const std::map<std::string, std::vector<double>>& cell_data = {},
                  const std::map<std::string, Eigen::MatrixXd>& point_vectors = {});

/// Writes a moving mesh (write_mesh_series) as write_exodus lays out `mesh` (coordinates: the
/// positions the motion starts from), a time step per step (ex_put_time) whose nodal
/// variables displacement_x/_y(/_z) = x − start carry the motion (the Exodus convention:
/// ParaView's reader adds them to the coordinates), then its fields as write_exodus's.
void write_exodus_series(const std::filesystem::path& file, const Mesh& mesh, int n_steps,
                         const std::function<MeshStep(int)>& step, const std::filesystem::path& shown);

}  // namespace meshmorph
