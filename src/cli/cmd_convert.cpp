// SPDX-License-Identifier: MIT
#include <memory>
#include <string>
#include <utility>

#include <CLI/CLI.hpp>

#include "meshmorph/app/quality_case.h"
#include "meshmorph/cli/commands.h"
#include "meshmorph/error.h"
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

Outcome run_convert(const ConvertArgs& a) {
  // What can be checked before reading, so that a usage error costs nothing.
  const WriteOptions options = convert_options(a.out, a.binary, a.msh22);
  Mesh mesh = read_mesh(a.in);
  log_detail(a.in + ": " + std::to_string(mesh.n_nodes()) + " nodes, " + std::to_string(mesh.n_cells()) +
             " cells, order " + std::to_string(mesh.order()));
  mesh = converted(std::move(mesh), a.order, a.in);
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
