// SPDX-License-Identifier: MIT
#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "meshmorph/app/commands.h"
#include "meshmorph/error.h"
#include "meshmorph/fem/elevate.h"
#include "meshmorph/io/mesh_io.h"
#include "meshmorph/log.h"

namespace meshmorph {

namespace {

struct ConvertArgs {
  std::string in, out;
  int order = 0;  // 0: keep the mesh's order
  bool binary = false;
  bool msh22 = false;
};

// Checks what can be checked before reading, so that a usage error costs nothing.
WriteOptions write_options(const ConvertArgs& a) {
  const std::string ext = std::filesystem::path(a.out).extension().string();
  if (ext != ".msh" && ext != ".vtu" && ext != ".mesh")
    throw InputError(a.out + ": unknown output format \"" + ext + "\" (expected .msh, .vtu or .mesh)");
  if (a.msh22 && ext != ".msh") throw InputError(a.out + ": --msh22 needs a .msh output file");
  if (a.binary && ext == ".mesh") throw InputError(a.out + ": --binary is not available for Medit .mesh output");
  WriteOptions options;
  options.binary = a.binary;
  if (a.msh22) options.format = MeshFormat::Msh22;
  return options;
}

Outcome run_convert(const ConvertArgs& a) {
  const WriteOptions options = write_options(a);
  Mesh mesh = read_mesh(a.in);
  log_detail(a.in + ": " + std::to_string(mesh.n_nodes()) + " nodes, " + std::to_string(mesh.n_cells()) +
             " cells, order " + std::to_string(mesh.order()));
  if (a.order > 0 && (a.order != mesh.order() || below_order(mesh, a.order))) {
    if (a.order < mesh.order())
      throw InputError(a.in + ": --order " + std::to_string(a.order) + " is below the mesh's order " +
                       std::to_string(mesh.order()) + " (order can only be raised)");
    for (const auto& block : mesh.cells)
      if (a.order > max_order_of(block.type))
        throw InputError(a.in + ": --order " + std::to_string(a.order) + " is above the highest for " +
                         std::string(name_of(block.type)) + " cells (" + std::to_string(max_order_of(block.type)) + ")");
    mesh = elevate_order(mesh, a.order);
  }
  write_mesh(a.out, mesh, options);
  log_info("wrote " + a.out + ": " + std::to_string(mesh.n_nodes()) + " nodes, " + std::to_string(mesh.n_cells()) +
           " cells, order " + std::to_string(mesh.order()));
  return Outcome::GoalReached;
}

}  // namespace

void add_convert_command(CLI::App& app, Command& run) {
  auto args = std::make_shared<ConvertArgs>();
  CLI::App* cmd = app.add_subcommand("convert", "Convert a mesh to another format, optionally raising its order");
  cmd->add_option("IN", args->in, "Input mesh (.msh 2.2/4.1, .vtu, .mesh)")->required();
  cmd->add_option("OUT", args->out, "Output mesh; the extension picks the format (.msh = MSH 4.1)")->required();
  cmd->add_option("--order", args->order, "Raise to order P with straight sides (1-4 simplices, 1-3 quads/hexes)")
      ->check(CLI::Range(1, 4))
      ->type_name("P");
  cmd->add_flag("--binary", args->binary, "Binary MSH, or base64 binary arrays in VTU");
  cmd->add_flag("--msh22", args->msh22, "Write MSH 2.2 instead of 4.1");
  cmd->callback([args, &run] { run = [args](std::ostream&) { return run_convert(*args); }; });
}

}  // namespace meshmorph
