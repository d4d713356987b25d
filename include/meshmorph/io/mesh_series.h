// SPDX-License-Identifier: MIT
#pragma once
#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "meshmorph/mesh/mesh.h"

namespace meshmorph {

/// One time step of a moving mesh (write_mesh_series): its time, the nodes' positions and the
/// fields they carry, laid out as WriteOptions's `cell_data` and `point_vectors`.
struct MeshStep {
  double time = 0;
  Eigen::MatrixXd x;  ///< Mesh::dim × n_nodes
  std::map<std::string, std::vector<double>> cell_data;
  std::map<std::string, Eigen::MatrixXd> point_vectors;
};

/// Whether `path`'s format holds a moving mesh's time steps in one file (CGNS .cgns, Exodus II
/// .exo/.e/.ex2; any case): the formats write_mesh_series writes.
bool is_series_format(const std::filesystem::path& path);

/// Writes the `n_steps` steps of a moving mesh into one file, atomically (io/atomic_file.h):
/// `mesh` gives the cells, the groups and the positions the motion starts from, `step(k)` the
/// steps in order (k = 0 … n_steps − 1, each asked for once, so that a caller need keep only
/// their positions), every step with the same fields. CGNS: the start as GridCoordinates, each
/// step as a GridCoordinates_t, a Vertex and a CellCenter FlowSolution_t, tied to its time by
/// BaseIterativeData_t and ZoneIterativeData_t; Exodus II: the start as the coordinates, each
/// step's motion (x − start) as the nodal variables displacement_x/_y/_z, its fields as nodal
/// and element variables at its time (docs/formats.md). Throws InputError (naming `path`) for
/// another format or what the format cannot hold, IoError when the file cannot be written.
void write_mesh_series(const std::filesystem::path& path, const Mesh& mesh, int n_steps,
                       const std::function<MeshStep(int)>& step);

}  // namespace meshmorph
