// SPDX-License-Identifier: MIT
// `mesh` level sets from files: the geometry layer sits above io (DESIGN §1,
// cmake/check_layering.cmake), so the compile step reads the background mesh itself.
#include <string>
#include <utility>

#include "geometry/detail/level_set_node.h"
#include "meshmorph/error.h"
#include "meshmorph/io/mesh_io.h"

namespace meshmorph::detail {

NodePtr load_background_field(const MeshLevelSet& s, int dim, const std::string& where) {
  const std::string file = s.file.string();
  Mesh mesh;
  // The reader's message names the file and the position; prefix the case entry.
  try {
    mesh = read_mesh(s.file);
  } catch (const InputError& e) {
    throw InputError(where + ".file: " + e.what());
  } catch (const IoError& e) {
    throw IoError(where + ".file: " + e.what());
  }
  if (mesh.dim != dim)
    throw InputError(where + ".file: " + file + " is a " + std::to_string(mesh.dim) + "D mesh, but the level set is " +
                     std::to_string(dim) + "D");
  const auto it = mesh.node_fields.find(s.field);
  if (it == mesh.node_fields.end()) {
    std::string names;
    for (const auto& [name, values] : mesh.node_fields) names += (names.empty() ? "\"" : ", \"") + name + "\"";
    throw InputError(where + ".field: " + file + " has no nodal field \"" + s.field + "\" (" +
                     (names.empty() ? std::string("it has no nodal fields") : "its nodal fields: " + names) + ")");
  }
  Eigen::VectorXd values = std::move(it->second);
  mesh.node_fields.clear();  // the background keeps only the field it interpolates
  return make_background_field(std::move(mesh), std::move(values),
                               where + ".field: nodal field \"" + s.field + "\" of " + file);
}

}  // namespace meshmorph::detail
