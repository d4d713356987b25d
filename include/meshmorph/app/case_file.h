// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "meshmorph/geometry/level_set.h"
#include "meshmorph/methods/boundary_motion.h"
#include "meshmorph/mesh/mesh.h"
#include "meshmorph/mesh/topology.h"

namespace meshmorph {

/// A parsed and validated case file (DESIGN §3.2). Paths are resolved against the folder of
/// the case file; unset optional keys stay empty.
struct CaseFile {
  std::filesystem::path file;        ///< the case file as given (used in messages)
  std::filesystem::path mesh;        ///< exists (empty where parse_case_file did not require it)
  std::optional<int> order;          ///< 1–4
  std::vector<BoundaryCondition> boundary;
  std::optional<LevelSet> interface;
  std::optional<LevelSet> trim;
  int steps = 1;                     ///< ≥ 1
  bool output_each_step = false;
  std::optional<double> dt;          ///< time between increments: written meshes carry mesh_velocity
  /// List the cells that are mirrored against their neighbours the right way round instead of
  /// refusing the mesh (orient_cells).
  bool reorient = false;
  nlohmann::json options = nlohmann::json::object();  ///< validated by the method (OptionReader)
  std::optional<std::filesystem::path> output;  ///< .msh, .vtu or .mesh
  std::optional<std::filesystem::path> report;
  std::vector<std::string> keys;     ///< the top-level keys given, in file order
};

/// Reads and validates a case file. Throws InputError whose message starts with the file
/// name and names the line and column (JSON syntax), or the key path
/// (`case.json: boundary[2].rotate.axis: expected 3 numbers`) for wrong types, unknown keys,
/// out-of-range values, missing files, malformed CSV displacement files (file:line) and
/// expressions that do not compile. Throws IoError when the file cannot be read.
CaseFile read_case_file(const std::filesystem::path& path);

/// The same, from JSON text; `file` names it in messages and is the base of relative paths.
/// Without `mesh_required` a case may leave out "mesh" (CaseFile::mesh stays empty): the
/// Python module's Morpher has its mesh in memory.
CaseFile parse_case_file(const std::string& text, const std::filesystem::path& file, bool mesh_required = true);

/// The case of a bare mesh (`meshmorph untangle MESH`, `optimize MESH`): no boundary entry (every
/// boundary node stays where it is), the defaults of every option; `path` names it in messages.
CaseFile bare_case(const std::filesystem::path& path);

/// Rejects the keys of `unused` that the case gives: `method` would ignore them, and a run
/// that silently leaves out what the user asked for (a `trim` to morph, `steps` to fit) is
/// not the run they asked for. Throws InputError naming the case file and the key.
void reject_unused_keys(const CaseFile& c, const std::string& method, std::initializer_list<std::string_view> unused);

/// Checks a case against its loaded mesh: every boundary group exists (by name or number),
/// every vector has mesh.dim entries, `rotate` has an axis exactly in 3D, cylinder and torus
/// are used only in 3D, and every node of a displacement table exists in the mesh with mesh.dim
/// components. Throws InputError naming the case file and the key path.
void check_case_against_mesh(const CaseFile& c, const Mesh& mesh);

/// The mesh's cells oriented alike (DESIGN §2: a valid mesh is injective, and a cell listed
/// mirrored against its neighbours folds it over itself, however a method moves the nodes).
/// Without the case's "reorient" such a mesh is bad input: InputError naming the mesh, how
/// many cells and the first. With it, those cells are listed mirrored back. Returns how many
/// cells were reoriented.
std::size_t orient_cells(const CaseFile& c, Mesh& mesh);
/// The same with the facets of `topology` (built for `mesh` as it is): the caller rebuilds
/// it when cells were reoriented (their facets' local numbers change).
std::size_t orient_cells(const CaseFile& c, Mesh& mesh, const Topology& topology);

/// Reads a displacement CSV: lines `node,dx,dy[,dz]` (the same number of columns on every
/// line), an optional header line, blank lines ignored. Throws InputError `file:line: ...`
/// for bad numbers, non-finite values, wrong column counts, node tags < 1 and repeated nodes.
DisplacementTable read_displacement_csv(const std::filesystem::path& path);

}  // namespace meshmorph
