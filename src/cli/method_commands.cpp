// SPDX-License-Identifier: MIT
// The subcommands morph, untangle, fit and deform: a case (untangle: or a mesh), -o and
// --report, and the run of each file cmd_<name>.cpp (untangle adds its own options there).
#include <memory>
#include <ostream>

#include <CLI/CLI.hpp>

#include "cli/detail/method_command.h"
#include "meshmorph/cli/commands.h"

namespace meshmorph {

void add_method_commands(CLI::App& app, Command& run, const int& threads) {
  struct Entry {
    detail::MethodHelp help;
    Outcome (*body)(const detail::MethodArgs&, int, std::ostream&);
  };
  const Entry entries[] = {
      {{"morph",
        "Move the mesh to follow a prescribed boundary motion (paper 000)",
        "CASE",
        "Case file (JSON, see docs/case-file.md)",
        "Output mesh (overrides the case's \"output\")"},
       &detail::run_morph},
      {{"fit",
        "Fit the mesh's interface or boundary to a level set (paper 003)",
        "CASE",
        "Case file (JSON, see docs/case-file.md)",
        "Output mesh (overrides the case's \"output\")"},
       &detail::run_fit},
      {{"deform",
        "CVT surface repair and Eikonal convection deformation (paper 004)",
        "CASE",
        "Case file (JSON, docs/case-file.md, docs/deform.md)",
        "Output mesh (overrides the case's \"output\")"},
       &detail::run_deform},
  };
  for (const Entry& e : entries) {
    detail::add_method_command(app, run, threads, e.help, std::make_shared<detail::MethodArgs>(), e.body);
    if (e.body == &detail::run_morph) detail::add_untangle_command(app, run, threads);  // in --help's order
  }
}

}  // namespace meshmorph
