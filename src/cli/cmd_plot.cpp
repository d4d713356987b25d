// SPDX-License-Identifier: MIT
// `meshmorph plot MESH [-o FILE.png|.svg] [--field F] [--reference MESH]`: a picture of a mesh
// coloured by a quality field, with its histogram.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "cli/detail/mesh_picture.h"
#include "cli/detail/output_files.h"
#include "cli/detail/plot_file.h"
#include "meshmorph/cli/commands.h"
#include "meshmorph/error.h"
#include "meshmorph/io/mesh_io.h"

namespace meshmorph {
namespace {

struct PlotArgs {
  std::string mesh;
  std::string output;     // -o; default MESH's name with .png, beside it
  std::string field;      // default: quality with a reference, else shape_quality
  std::string reference;  // --reference MESH
};

std::string counts(const Mesh& m) {
  return std::to_string(m.dim) + "D, " + std::to_string(m.n_nodes()) + " nodes, " + std::to_string(m.n_cells()) + " cells";
}

Outcome run_plot(const PlotArgs& a, std::ostream& out) {
  const std::filesystem::path mesh_path(a.mesh);
  const std::filesystem::path output =
      a.output.empty() ? std::filesystem::path(mesh_path).replace_extension(".png") : std::filesystem::path(a.output);
  detail::check_plot_path(output, "-o");
  const Mesh mesh = read_mesh(mesh_path);
  std::optional<Mesh> reference;
  if (!a.reference.empty()) {
    reference = read_mesh(a.reference);
    if (reference->dim != mesh.dim || reference->n_nodes() != mesh.n_nodes() || reference->n_cells() != mesh.n_cells())
      throw InputError("--reference: " + a.reference + " (" + counts(*reference) + ") is not " + a.mesh + " (" +
                       counts(mesh) + ") before it moved: it needs the same nodes and cells");
  }
  detail::check_outputs({{"-o", output, false}});
  const std::string field = !a.field.empty() ? a.field : reference ? "quality" : "shape_quality";
  detail::CellField f = detail::cell_field(mesh, field, reference ? &*reference : nullptr);

  const std::vector<bool> worst = detail::worst_cells(f.values, 0.05);
  double low = HUGE_VAL, high = -HUGE_VAL;
  for (const double v : f.values)
    if (std::isfinite(v)) low = std::min(low, v), high = std::max(high, v);
  detail::write_plot(output, {{&mesh, f.values, mesh_path.filename().string()}}, f.label);
  char line[160];
  std::snprintf(line, sizeof line, "plot     %s: %s min %.4g, max %.4g; %zu worst cells outlined\n", a.mesh.c_str(),
                field.c_str(), low, high, static_cast<std::size_t>(std::count(worst.begin(), worst.end(), true)));
  out << line << "wrote    " << output.string() << "\n";
  return Outcome::GoalReached;
}

}  // namespace

void add_plot_command(CLI::App& app, Command& run) {
  auto args = std::make_shared<PlotArgs>();
  CLI::App* cmd = app.add_subcommand(
      "plot", "Picture of a mesh (2D; 3D: its boundary, cut in half) coloured by a quality field, with a histogram");
  cmd->add_option("MESH", args->mesh, "Mesh file")->required();
  cmd->add_option("-o,--output", args->output, "Picture to write, by its extension (default: MESH's name with .png)")
      ->type_name("FILE.png|.svg");
  std::vector<std::string> fields(detail::kPlotFields.begin(), detail::kPlotFields.end());
  cmd->add_option("--field", args->field,
                  "quality (1/eta against --reference) | shape_quality | scaled_jacobian | displacement (from --reference); "
                  "default: quality with --reference, else shape_quality")
      ->check(CLI::IsMember(fields));
  cmd->add_option("--reference", args->reference, "The mesh before it moved: same nodes and cells")->type_name("MESH");
  cmd->callback([args, &run] { run = [args](std::ostream& out) { return run_plot(*args, out); }; });
}

}  // namespace meshmorph
