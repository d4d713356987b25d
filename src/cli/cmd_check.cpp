// SPDX-License-Identifier: MIT
// `meshmorph check CASE.json`: validates a case file against its mesh without running a
// method, so a user (or a script) finds every bad key, group and file before a long run.
#include <algorithm>
#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "cli/detail/output_files.h"
#include "meshmorph/methods/boundary_motion.h"
#include "meshmorph/app/case_file.h"
#include "meshmorph/cli/commands.h"
#include "meshmorph/fem/validity.h"
#include "meshmorph/io/mesh_io.h"

namespace meshmorph {
namespace {

std::string motion_name(const Motion& m) {
  static constexpr const char* names[] = {"fixed", "translate", "rotate", "scale", "project", "displace", "slide"};
  return names[m.index()];
}

Outcome run_check(const std::string& path, std::ostream& out) {
  const CaseFile c = read_case_file(path);
  const Mesh mesh = read_mesh(c.mesh);
  check_case_against_mesh(c, mesh);
  detail::check_outputs(&c, c.output, c.report);
  // Where every motion is rigid or tabulated, its targets are the same for morph, untangle and
  // deform: resolve them, so a node that two groups send to different places is found here.
  // A projection is left to the method: fit moves along it, the others to its closest point.
  if (std::none_of(c.boundary.begin(), c.boundary.end(),
                   [](const BoundaryCondition& b) { return std::holds_alternative<ProjectMotion>(b.motion); }))
    BoundaryMotion(c.boundary, c.file.string(), mesh, build_topology(mesh));
  Mesh oriented = mesh;
  const std::size_t reoriented = orient_cells(c, oriented);
  const std::size_t inverted = count_invalid_cells(oriented);

  out << "case     " << path << "\n"
      << "mesh     " << c.mesh.string() << ": " << mesh.dim << "D, " << mesh.n_nodes() << " nodes, " << mesh.n_cells()
      << " cells, order " << mesh.order() << (c.order && *c.order > mesh.order() ? " (elevated to " + std::to_string(*c.order) + ")" : "")
      << "\n";
  for (const auto& bc : c.boundary) {
    const auto group = mesh.find_group(bc.group);
    out << "boundary " << bc.key_path << ": group \"" << bc.group << "\" (" << mesh.group_nodes(*group).size()
        << " nodes): " << motion_name(bc.motion) << "\n";
  }
  if (reoriented > 0) out << "reorient " << reoriented << " cells listed mirrored against their neighbours\n";
  out << "steps    " << c.steps << "\n"
      << "inverted " << inverted << " of " << mesh.n_cells() << " input cells\n";
  return inverted == 0 ? Outcome::GoalReached : Outcome::GoalMissed;
}

}  // namespace

void add_check_command(CLI::App& app, Command& run) {
  auto path = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand(
      "check", "Validate a case file and its mesh without running a method (exit 1: the input mesh has inverted cells)");
  cmd->add_option("CASE", *path, "Case file (JSON, see docs/case-file.md)")->required();
  cmd->callback([path, &run] { run = [path](std::ostream& out) { return run_check(*path, out); }; });
}

}  // namespace meshmorph
