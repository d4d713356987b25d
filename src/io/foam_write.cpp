// SPDX-License-Identifier: MIT
#include <algorithm>
#include <charconv>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "io/detail/out_buffer.h"
#include "meshmorph/error.h"
#include "meshmorph/io/atomic_file.h"
#include "meshmorph/io/foam.h"

namespace meshmorph {
namespace {

namespace fs = std::filesystem;

// "case/0.1/" names the folder 0.1 too.
fs::path without_slash(const fs::path& path) { return path.filename().empty() ? path.parent_path() : path; }

// OpenFOAM names a time folder by the time, a number.
bool is_time(std::string_view name) {
  double t = 0;
  const auto [end, ec] = std::from_chars(name.data(), name.data() + name.size(), t);
  return !name.empty() && ec == std::errc() && end == name.data() + name.size();
}

fs::path case_of(const fs::path& time_folder) {
  const fs::path parent = without_slash(time_folder).parent_path();
  return parent.empty() ? fs::path(".") : parent;
}

// The cells as sorted lists of their corners, sorted: the same for two meshes whose cells
// stand on the same nodes, whatever the cells' order and the order of their nodes.
std::vector<std::vector<std::int32_t>> corner_sets(const Mesh& mesh) {
  std::vector<std::vector<std::int32_t>> sets;
  sets.reserve(mesh.n_cells());
  for (const CellBlock& b : mesh.cells)
    for (std::size_t c = 0; c < b.n_cells(); ++c) {
      std::vector<std::int32_t> s(b.cell(c), b.cell(c) + n_corners_of(b.type));
      std::sort(s.begin(), s.end());
      sets.push_back(std::move(s));
    }
  std::sort(sets.begin(), sets.end());
  return sets;
}

}  // namespace

bool is_foam_time_folder(const fs::path& path) {
  std::error_code ec;
  return is_time(without_slash(path).filename().string()) &&
         fs::is_directory(case_of(path) / "constant" / "polyMesh", ec);
}

void write_foam_points(const fs::path& time_folder, const Mesh& mesh) {
  const fs::path folder = without_slash(time_folder);
  const std::string time = folder.filename().string();
  if (!is_time(time))
    throw InputError(time_folder.string() + ": an OpenFOAM time folder is named by its time (such as 0.001), not \"" +
                     time + "\"");
  const fs::path constant = case_of(folder) / "constant" / "polyMesh";
  const Mesh original = read_foam(constant);
  const std::string only = ": only a mesh read from this case's polyMesh can be written as its points";
  if (mesh.dim != 3 || original.n_nodes() != mesh.n_nodes())
    throw InputError(time_folder.string() + ": the mesh has " + std::to_string(mesh.n_nodes()) + " nodes (" +
                     std::to_string(mesh.dim) + "D) where " + constant.string() + " has " +
                     std::to_string(original.n_nodes()) + " points" + only);
  if (corner_sets(mesh) != corner_sets(original))
    throw InputError(time_folder.string() + ": the mesh's cells are not those of " + constant.string() +
                     " on the same points (another mesh, or its nodes renumbered)" + only);
  std::error_code mk;
  fs::create_directories(folder / "polyMesh", mk);
  if (mk) throw IoError(folder.string() + "/polyMesh: cannot create the folder: " + mk.message());
  write_atomically(folder / "polyMesh" / "points", false, [&](std::ostream& out) {
    detail::OutBuffer o(out);
    o << "FoamFile\n{\n    version     2.0;\n    format      ascii;\n    class       vectorField;\n"
         "    location    \""
      << time << "/polyMesh\";\n    object      points;\n}\n\n"
      << mesh.n_nodes() << "\n(\n";
    for (Eigen::Index j = 0; j < mesh.x.cols(); ++j)
      o << '(' << mesh.x(0, j) << ' ' << mesh.x(1, j) << ' ' << mesh.x(2, j) << ")\n";
    o << ")\n";
    o.flush();
  });
}

}  // namespace meshmorph
