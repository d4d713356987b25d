// SPDX-License-Identifier: MIT
#include "meshmorph/app/quality_case.h"

#include <cmath>
#include <filesystem>

#include "app/detail/method_output.h"
#include "meshmorph/error.h"
#include "meshmorph/fem/elevate.h"
#include "meshmorph/io/foam.h"
#include "meshmorph/io/mesh_io.h"

namespace meshmorph {

QualityOutput run_quality(const Mesh& mesh, const std::string& name, const Mesh* reference) {
  if (reference) {
    bool same = reference->dim == mesh.dim && reference->n_nodes() == mesh.n_nodes() && reference->cells.size() == mesh.cells.size();
    for (std::size_t i = 0; same && i < mesh.cells.size(); ++i)
      same = reference->cells[i].type == mesh.cells[i].type && reference->cells[i].order == mesh.cells[i].order &&
             reference->cells[i].nodes == mesh.cells[i].nodes;
    if (!same) throw InputError(name + ": reference: not the same cells and nodes as the mesh");
  }
  QualityOutput out;
  const QualityReport& q = out.quality = quality_report(mesh, reference);
  const bool valid = q.valid();
  Report& r = out.report;
  r.method = "quality";
  detail::fill_measures(r, mesh, q);
  r.converged = valid;
  r.message = valid ? "all elements valid" : detail::invalid_message(q);
  out.extra["mesh"] = name;
  out.extra["mean_shape_quality"] = std::isfinite(q.mean_shape_quality) ? nlohmann::ordered_json(q.mean_shape_quality)
                                                                        : nlohmann::ordered_json(nullptr);
  out.extra["shape_histogram"] = q.shape_histogram;
  return out;
}

WriteOptions convert_options(const std::string& output, bool binary, bool msh22) {
  const std::string ext = std::filesystem::path(output).extension().string();
  const bool foam = !known_mesh_format(output) && is_foam_time_folder(output);
  if (!known_mesh_format(output) && !foam)
    throw InputError(output + ": unknown output format \"" + ext +
                     "\" (expected .msh, .vtu, .mesh, .su2, .cgns, .exo or an OpenFOAM case's time folder)");
  if (msh22 && ext != ".msh") throw InputError(output + ": --msh22 needs a .msh output file");
  if (binary && (ext == ".mesh" || ext == ".su2" || foam))
    throw InputError(output + ": --binary is not available for " + (foam ? "OpenFOAM points" : ext) + " output");
  WriteOptions options;
  options.binary = binary;
  if (msh22) options.format = MeshFormat::Msh22;
  return options;
}

Mesh converted(Mesh mesh, int order, const std::string& name) {
  if (order <= 0 || (order == mesh.order() && !below_order(mesh, order))) return mesh;
  if (order < mesh.order())
    throw InputError(name + ": --order " + std::to_string(order) + " is below the mesh's order " +
                     std::to_string(mesh.order()) + " (order can only be raised)");
  for (const auto& block : mesh.cells)
    if (order > max_order_of(block.type))
      throw InputError(name + ": --order " + std::to_string(order) + " is above the highest for " +
                       std::string(name_of(block.type)) + " cells (" + std::to_string(max_order_of(block.type)) + ")");
  return elevate_order(mesh, order);
}

}  // namespace meshmorph
