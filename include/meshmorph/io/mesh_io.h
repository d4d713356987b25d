// SPDX-License-Identifier: MIT
#pragma once
#include <filesystem>
#include <string_view>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "meshmorph/mesh/mesh.h"

namespace meshmorph {

enum class MeshFormat {
  Msh41, Msh22, Vtu, Medit,
  Su2, Foam,  ///< SU2 .su2; OpenFOAM polyMesh (points of a time folder: io/foam.h)
  Cgns, Exodus,
};

/// How write_mesh writes. `format` defaults to the one implied by the extension
/// (.msh → MSH 4.1, .vtu → VTU, .mesh → Medit, .su2 → SU2, .cgns → CGNS, .exo/.e/.ex2 →
/// Exodus II, the time folder of an OpenFOAM case → its polyMesh/points, write_foam_points).
struct WriteOptions {
  std::optional<MeshFormat> format;
  bool binary = false;  ///< MSH binary / VTU base64-encoded binary arrays
  /// Per-cell scalar arrays (one value per cell of Mesh::cells, blocks concatenated): VTU
  /// CellData, MSH $ElementData, a CGNS CellCenter FlowSolution_t, Exodus II element
  /// variables; ignored by Medit and SU2.
  std::map<std::string, std::vector<double>> cell_data;
  /// Per-node vector arrays (Mesh::dim × n_nodes each; the displacement and mesh velocity of
  /// a morph): VTU PointData of 3 components (z = 0 in 2D), MSH $NodeData of 3 components, a
  /// CGNS Vertex FlowSolution_t, Exodus II nodal variables (but `displacement`: io/exodus.h);
  /// ignored by Medit and SU2.
  std::map<std::string, Eigen::MatrixXd> point_vectors;
};

/// Reads a mesh; the format comes from the extension (.msh: MSH 2.2 or 4.1, ASCII or
/// binary, detected from its header; .vtu; .mesh; .su2; .cgns; .exo, .e, .ex2; an OpenFOAM
/// case, polyMesh or time folder, or a .foam file in a case: read_foam). Nodes are converted to the internal
/// (Gmsh) ordering. Throws InputError naming the file and the line or byte offset for
/// malformed content, and IoError when the file cannot be read.
Mesh read_mesh(const std::filesystem::path& path);

/// Whether read_mesh and write_mesh know the format of `path`'s extension (any case).
bool known_mesh_format(const std::filesystem::path& path);

/// Why a physical-group name cannot be stored in every format, or none: MSH keeps names in
/// quotes on one line and XML holds no control byte, so a name must be valid UTF-8 without
/// control bytes (below 0x20, 0x7f) or double quotes. Readers refuse such names at their
/// line, writers before writing anything.
std::optional<std::string> group_name_problem(std::string_view name);

/// Writes a mesh atomically (io/atomic_file.h). Throws InputError when the format cannot
/// hold the mesh (e.g. curved cells in Medit, a group name of group_name_problem), IoError
/// when the file cannot be written.
void write_mesh(const std::filesystem::path& path, const Mesh& mesh, const WriteOptions& options = {});

}  // namespace meshmorph
