// SPDX-License-Identifier: MIT
#pragma once
#include <map>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "io/detail/cgns_file.h"
#include "meshmorph/mesh/mesh.h"

namespace meshmorph::detail {

/// Writes `mesh` into the open file `f` as write_cgns lays it out (base "Base", zone "Zone",
/// GridCoordinates = mesh.x, a section per block, families, BCs and sub-regions); returns the
/// base's and the zone's indices.
std::pair<int, int> write_cgns_mesh(const CgnsFile& f, const Mesh& mesh);

/// The FlowSolution_t nodes write_cgns_fields wrote (empty names: none).
struct CgnsSolutions {
  std::string vertex, cells;
};

/// Writes the fields of `mesh`'s zone: `point_vectors` as the Vertex FlowSolution_t `vertex`
/// (components <Name>X/Y/Z, the SIDS names GridVelocity for mesh_velocity and Displacement
/// for displacement), `cell_data` as the CellCenter FlowSolution_t `cells` (one value per
/// cell of Mesh::cells, which are the zone's elements 1 … n_cells). A node without fields is
/// not written. Throws InputError for a name CGNS cannot hold (over 32 characters, '/').
CgnsSolutions write_cgns_fields(const CgnsFile& f, int base, int zone, const Mesh& mesh, const std::string& vertex,
                                const std::string& cells, const std::map<std::string, std::vector<double>>& cell_data,
                                const std::map<std::string, Eigen::MatrixXd>& point_vectors);

}  // namespace meshmorph::detail
